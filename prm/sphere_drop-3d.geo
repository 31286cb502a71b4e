// A quarter of a sphere of radius R (material 1, centre at height R + gap
// on the z axis) above a quarter of a plate (material 2, top face z = 0),
// cut by the symmetry planes x = 0 (boundary id 1) and y = 0 (boundary id
// 2); every other face has boundary id 0. The mesh is refined to hf
// within 0.2 R of the point under the sphere and coarsens to hc at 0.5 R.
// Other sizes: gmsh -setnumber hf ..., or a .geo that sets them and
// Includes this file.
SetFactory("OpenCASCADE");
DefineConstant[ R = 0.05, gap = 0.0005, hf = 0.00125, hc = 0.005, L = 0.04, H = 0.02 ];
Sphere(1) = {0, 0, R + gap, R, -Pi / 2, Pi / 2, Pi / 2};
Box(2) = {0, 0, -H, L, L, H};
Physical Volume(1) = {1};
Physical Volume(2) = {2};
e = 1e-5;
sx() = Surface In BoundingBox{-e, -e, gap - e, e, R + e, 2 * R + gap + e};
sy() = Surface In BoundingBox{-e, -e, gap - e, R + e, e, 2 * R + gap + e};
all() = Boundary{ Volume{1, 2}; };
Physical Surface(1) = {sx()};
Physical Surface(2) = {sy()};
Physical Surface(0) = {all()};
Physical Surface(0) -= {sx(), sy()};
Point(100) = {0, 0, gap / 2};
Field[1] = Distance;
Field[1].PointsList = {100};
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = hf;
Field[2].SizeMax = hc;
Field[2].DistMin = 0.2 * R;
Field[2].DistMax = 0.5 * R;
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Mesh.RandomSeed = 1;
