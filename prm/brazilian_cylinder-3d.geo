// Brazilian test in 3D: a rock cylinder of diameter D = 2 R and thickness
// 2 H (material 1, axis along z) between two steel loading jaws with
// circular seats over 2 alpha = 15 degrees. Half of the thickness is
// modelled: the mid plane z = 0 is a plane of symmetry (boundary id 1,
// roller z). The loaded plane x = 0 is embedded in the mesh (the cylinder
// is two half cylinders that share it), so that joints lie on it. Top jaw
// material 2, bottom jaw material 3; every other face has boundary id 0.
// The mesh size is hf within band of the loaded plane and grows to hc at
// 2 band. The gap between the cylinder and each seat exceeds the sagitta
// hf^2 / (8 R) = 20 um of the seat's facets, so that the meshed jaws do not
// touch the meshed cylinder at the start. Other sizes: gmsh -setnumber
// hf ..., or a .geo that sets them and Includes this file.
SetFactory("OpenCASCADE");
DefineConstant[ R = 0.025, H = 0.005, gap = 5e-5, hf = 0.002, hc = 0.004,
                band = 0.004 ];
alpha = 7.5 * Pi / 180; Rs = R + gap; w = 0.012; tj = 0.008;
Cylinder(1) = {0, 0, 0, 0, 0, H, R, Pi};
Rotate {{0, 0, 1}, {0, 0, 0}, -Pi / 2} { Volume{1}; }
Cylinder(2) = {0, 0, 0, 0, 0, H, R, Pi};
Rotate {{0, 0, 1}, {0, 0, 0}, Pi / 2} { Volume{2}; }
disc() = BooleanFragments{ Volume{1}; Delete; }{ Volume{2}; Delete; };
// the jaws: a block with a seat of radius Rs cut out of it
Box(3) = {-w, Rs * Cos(alpha), 0, 2 * w, R + tj - Rs * Cos(alpha), H};
Box(4) = {-w, -R - tj, 0, 2 * w, R + tj - Rs * Cos(alpha), H};
Cylinder(5) = {0, 0, -1, 0, 0, H + 2, Rs};
top() = BooleanDifference{ Volume{3}; Delete; }{ Volume{5}; };
bottom() = BooleanDifference{ Volume{4}; Delete; }{ Volume{5}; Delete; };
Physical Volume(1) = {disc()};
Physical Volume(2) = {top()};
Physical Volume(3) = {bottom()};
e = 1e-6;
mid() = Surface In BoundingBox{-R - e, -R - e, -e, R + e, R + e, e};
all() = Unique(Abs(Boundary{ Volume{disc(), top(), bottom()}; }));
Physical Surface(1) = {mid()};
Physical Surface(0) = {all()};
plane() = Surface In BoundingBox{-e, -R - e, -e, e, R + e, H + e};
Physical Surface(0) -= {mid(), plane()};
// fine within band of the loaded plane x = 0, coarse elsewhere
Field[1] = Distance;
Field[1].SurfacesList = {plane()};
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = hf;
Field[2].SizeMax = hc;
Field[2].DistMin = band;
Field[2].DistMax = 2 * band;
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Mesh.RandomSeed = 1;
