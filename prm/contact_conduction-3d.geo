// Two blocks pressed together: block 1 (material 1) [0, 0.05]^2 x [0, 0.1],
// block 2 (material 2) [0, 0.05]^2 x [0.1 - delta, 0.2 - delta], so that
// they overlap by delta = 10 micrometres across the contact z = 0.1.
// Separate volumes, meshed apart: no joints between them, heat crosses only
// by contact. Boundary id 1: the face z = 0; 2: the face z = 0.2 - delta;
// 0: the sides. Another mesh size: a .geo that sets h = ... and Includes
// this file.
SetFactory("OpenCASCADE");
DefineConstant[ h = 0.0125 ];
DefineConstant[ delta = 1e-5 ];
Box(1) = {0, 0, 0, 0.05, 0.05, 0.1};
Box(2) = {0, 0, 0.1 - delta, 0.05, 0.05, 0.1};
e = 1e-7;
Physical Volume(1) = {1};
Physical Volume(2) = {2};
Physical Surface(1) = {Surface In BoundingBox{-e, -e, -e, 0.05 + e, 0.05 + e, e}};
Physical Surface(2) = {Surface In BoundingBox{-e, -e, 0.2 - delta - e,
                                             0.05 + e, 0.05 + e, 0.2 - delta + e}};
// the sides x = 0, 0.05 and y = 0, 0.05 of both, and the two faces at the
// contact
Physical Surface(0) = {Surface In BoundingBox{-e, -e, -e, e, 0.05 + e, 0.2},
                       Surface In BoundingBox{0.05 - e, -e, -e, 0.05 + e, 0.05 + e, 0.2},
                       Surface In BoundingBox{-e, -e, -e, 0.05 + e, e, 0.2},
                       Surface In BoundingBox{-e, 0.05 - e, -e, 0.05 + e, 0.05 + e, 0.2},
                       Surface In BoundingBox{-e, -e, 0.1 - delta - e,
                                             0.05 + e, 0.05 + e, 0.1 + e}};
Mesh.MeshSizeMin = h;
Mesh.MeshSizeMax = h;
Mesh.RandomSeed = 1;
