// The 13 x 1 mm disc of paper 5.6 in 3D (prm/thermal_shock_disc-3d.prm):
// tetrahedra of size h_rim within 1.5 mm of the rim, growing to h_core at
// 3.5 mm from it (the thermal layer of the quench is a fraction of a
// millimetre deep while cracks start). Boundary ids: 1 the mantle (rim),
// 2 the bottom face z = -H/2, 3 the top face; material id 0. Another rim
// size: a .geo that sets h_rim = ...; and Includes this file (gmsh keeps a
// value set before DefineConstant).
SetFactory("OpenCASCADE");
R = 6.5e-3; H = 1e-3;
DefineConstant[ h_rim = 0.25e-3, h_core = 0.8e-3 ];
Cylinder(1) = {0, 0, -H / 2, 0, 0, H, R};
eps = 1e-6;
bottom() = Surface In BoundingBox{-R - eps, -R - eps, -H / 2 - eps, R + eps, R + eps, -H / 2 + eps};
top() = Surface In BoundingBox{-R - eps, -R - eps, H / 2 - eps, R + eps, R + eps, H / 2 + eps};
all() = Boundary{ Volume{1}; };
mantle() = all();
mantle() -= bottom();
mantle() -= top();
Physical Surface(1) = {mantle()};
Physical Surface(2) = {bottom()};
Physical Surface(3) = {top()};
Physical Volume(0) = {1};
Field[1] = Distance;
Field[1].SurfacesList = {mantle()};
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = h_rim;
Field[2].SizeMax = h_core;
Field[2].DistMin = 1.5e-3;
Field[2].DistMax = 3.5e-3;
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
