// Two cubes of 0.1 m side, 5 mm apart along x, separate bodies: material 1
// (the left cube, corner at the origin) and material 2 (the right one,
// shifted by 0.02 m in y and 0.01 m in z, so that the impact is
// off-centre); boundary id 0 on all faces. Another mesh size: a .geo that
// sets h = ...; and Includes this file.
SetFactory("OpenCASCADE");
DefineConstant[ h = 0.025 ];
Box(1) = {0, 0, 0, 0.1, 0.1, 0.1};
Box(2) = {0.105, 0.02, 0.01, 0.1, 0.1, 0.1};
Physical Volume(1) = {1};
Physical Volume(2) = {2};
Physical Surface(0) = {Boundary{ Volume{1, 2}; }};
Mesh.MeshSizeMin = h;
Mesh.MeshSizeMax = h;
Mesh.RandomSeed = 1;
