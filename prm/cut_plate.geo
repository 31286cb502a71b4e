// The paper's 1 x 0.25 m plate with a mesh line at x = 0.5 where a
// pre-existing crack (Discrete mechanics/Initial cracks) can cut it in two.
// Boundary ids: 0 left, 1 right, 2 bottom, 3 top.
h = 0.05;
Point(1) = {0, 0, 0, h}; Point(2) = {0.5, 0, 0, h}; Point(3) = {1, 0, 0, h};
Point(4) = {1, 0.25, 0, h}; Point(5) = {0.5, 0.25, 0, h}; Point(6) = {0, 0.25, 0, h};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 5};
Line(5) = {5, 6}; Line(6) = {6, 1}; Line(7) = {2, 5};
Curve Loop(1) = {1, 2, 3, 4, 5, 6}; Plane Surface(1) = {1};
Line{7} In Surface{1};
Physical Surface(0) = {1};
Physical Curve(0) = {6};
Physical Curve(1) = {3};
Physical Curve(2) = {1, 2};
Physical Curve(3) = {4, 5};
Mesh.RandomSeed = 1;
