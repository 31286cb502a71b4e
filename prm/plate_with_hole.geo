// A quarter of a square plate with a central circular hole: the plate is
// 2L x 2L, the hole of radius a; the quarter x >= 0, y >= 0 with symmetry
// planes on x = 0 and y = 0. The mesh is graded: element size h_min on the
// hole, growing linearly with the distance from it to h_max at d_max.
// Boundary ids (Physical Curve): 0 symmetry x = 0, 1 right edge x = L,
// 2 symmetry y = 0, 3 top edge y = L, 4 the hole. Material id 0.
a = 0.01; L = 0.1;
h_min = 0.001; h_max = 0.008; d_max = 0.06;
Point(1) = {0, 0, 0, h_max};                 // the hole's centre
Point(2) = {a, 0, 0, h_min}; Point(3) = {L, 0, 0, h_max};
Point(4) = {L, L, 0, h_max}; Point(5) = {0, L, 0, h_max};
Point(6) = {0, a, 0, h_min};
Line(1) = {2, 3}; Line(2) = {3, 4}; Line(3) = {4, 5}; Line(4) = {5, 6};
Circle(5) = {6, 1, 2};
Curve Loop(1) = {1, 2, 3, 4, 5}; Plane Surface(1) = {1};
Physical Surface(0) = {1};
Physical Curve(0) = {4};
Physical Curve(1) = {2};
Physical Curve(2) = {1};
Physical Curve(3) = {3};
Physical Curve(4) = {5};
// the grading: size = h_min on the hole, h_max from d_max on
Field[1] = Distance;
Field[1].CurvesList = {5};
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = h_min;
Field[2].SizeMax = h_max;
Field[2].DistMin = 0;
Field[2].DistMax = d_max;
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Mesh.RandomSeed = 1;
