// Brazilian test: a disc of diameter 50 mm (material 1) between two steel
// loading jaws with circular seats (loading arcs of 2 alpha = 15 degrees,
// the arc-loaded "Hondros" configuration): bottom jaw (material 3) fixed,
// top jaw (material 2) driven down. Separate surfaces: no joints between
// disc and jaws, only contact.
R = 0.025; h = 0.0015; hp = 0.002;
// the gap exceeds the sagitta h^2/(8R) of the polygonal seat, so that the
// meshed jaws do not overlap the meshed disc at the start
gap = 5e-5;
alpha = 7.5 * Pi / 180; Rs = R + gap; w = 0.012; t = 0.008;
Point(1) = {0, 0, 0, h};
Point(2) = {R, 0, 0, h}; Point(3) = {0, R, 0, h};
Point(4) = {-R, 0, 0, h}; Point(5) = {0, -R, 0, h};
Circle(1) = {2, 1, 3}; Circle(2) = {3, 1, 4};
Circle(3) = {4, 1, 5}; Circle(4) = {5, 1, 2};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
// the loaded diameter is a mesh line, so that joints lie along it: a crack
// can then run straight, and the joints there carry the full tensile stress
// (on unstructured edges inclined by theta it is sigma (1 - 4 sin^2 theta))
Line(5) = {5, 3};
Line{5} In Surface{1};
// top jaw: a seat of radius Rs over +-alpha, then flat shoulders
Point(11) = {Rs * Sin(alpha), Rs * Cos(alpha), 0, hp};
Point(12) = {-Rs * Sin(alpha), Rs * Cos(alpha), 0, hp};
Point(13) = {-w, Rs * Cos(alpha), 0, hp}; Point(14) = {-w, R + t, 0, hp};
Point(15) = {w, R + t, 0, hp};            Point(16) = {w, Rs * Cos(alpha), 0, hp};
Circle(11) = {11, 1, 12};
Line(12) = {12, 13}; Line(13) = {13, 14}; Line(14) = {14, 15};
Line(15) = {15, 16}; Line(16) = {16, 11};
Curve Loop(2) = {11, 12, 13, 14, 15, 16}; Plane Surface(2) = {2};
// bottom jaw, the mirror image
Point(21) = {-Rs * Sin(alpha), -Rs * Cos(alpha), 0, hp};
Point(22) = {Rs * Sin(alpha), -Rs * Cos(alpha), 0, hp};
Point(23) = {w, -Rs * Cos(alpha), 0, hp}; Point(24) = {w, -R - t, 0, hp};
Point(25) = {-w, -R - t, 0, hp};          Point(26) = {-w, -Rs * Cos(alpha), 0, hp};
Circle(21) = {21, 1, 22};
Line(22) = {22, 23}; Line(23) = {23, 24}; Line(24) = {24, 25};
Line(25) = {25, 26}; Line(26) = {26, 21};
Curve Loop(3) = {21, 22, 23, 24, 25, 26}; Plane Surface(3) = {3};
Physical Surface(1) = {1};
Physical Surface(2) = {2};
Physical Surface(3) = {3};
Physical Curve(0) = {1, 2, 3, 4};
Physical Curve(1) = {11, 12, 13, 14, 15, 16, 21, 22, 23, 24, 25, 26};
Mesh.RandomSeed = 1;
