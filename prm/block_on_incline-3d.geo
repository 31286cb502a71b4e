// A block (material 2, 0.1 x 0.1 x 0.05 m) resting on a fixed base
// (material 1, 0.6 x 0.5 x 0.1 m): two separate volumes whose meshes only
// touch on the face z = 0 (no joints between them). The incline is made by
// tilting gravity, so the base stays horizontal. Boundary id 0 on all
// faces. Another block mesh size: a .geo that sets hk = ...; and Includes
// this file.
SetFactory("OpenCASCADE");
DefineConstant[ hb = 0.15, hk = 0.05 ];
Box(1) = {-0.2, -0.2, -0.1, 0.6, 0.5, 0.1};
Box(2) = {0, 0, 0, 0.1, 0.1, 0.05};
Physical Volume(1) = {1};
Physical Volume(2) = {2};
Physical Surface(0) = {Boundary{ Volume{1, 2}; }};
MeshSize{ PointsOf{ Volume{1}; } } = hb;
MeshSize{ PointsOf{ Volume{2}; } } = hk;
Mesh.RandomSeed = 1;
