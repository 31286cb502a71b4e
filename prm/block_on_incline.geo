// A block (material 2, 0.1 x 0.05 m) resting on a fixed base (material 1).
// The incline is made by tilting gravity, so the base stays horizontal.
hb = 0.05; hk = 0.0125;
Point(1) = {-0.3, -0.1, 0, hb}; Point(2) = {0.6, -0.1, 0, hb};
Point(3) = {0.6, 0, 0, hb};     Point(4) = {-0.3, 0, 0, hb};
Point(5) = {0, 0, 0, hk};       Point(6) = {0.1, 0, 0, hk};
Point(7) = {0.1, 0.05, 0, hk};  Point(8) = {0, 0.05, 0, hk};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Line(5) = {5, 6}; Line(6) = {6, 7}; Line(7) = {7, 8}; Line(8) = {8, 5};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Curve Loop(2) = {5, 6, 7, 8}; Plane Surface(2) = {2};
Physical Surface(1) = {1};
Physical Surface(2) = {2};
Physical Curve(0) = {1, 2, 3, 4, 5, 6, 7, 8};
Mesh.RandomSeed = 1;
