// Three separate blocks for the rank-independence test of the contact
// search by bounding boxes (tests/CMakeLists.txt, mpi.discrete_ranks_far_contact):
// a small projectile (material 1, the first triangles: rank 0 of 3), a
// bystander block far to the lower left (material 2, most of rank 1) and a
// target block 5 mm to the right of the projectile (material 3, rank 2).
hp = 0.004;  // projectile and target
hb = 0.011;  // bystander
Point(1) = {0, 0, 0, hp};      Point(2) = {0.04, 0, 0, hp};
Point(3) = {0.04, 0.04, 0, hp}; Point(4) = {0, 0.04, 0, hp};
Point(5) = {-0.3, -0.3, 0, hb}; Point(6) = {-0.1, -0.3, 0, hb};
Point(7) = {-0.1, -0.1, 0, hb}; Point(8) = {-0.3, -0.1, 0, hb};
Point(9) = {0.045, -0.01, 0, hp}; Point(10) = {0.095, -0.01, 0, hp};
Point(11) = {0.095, 0.04, 0, hp}; Point(12) = {0.045, 0.04, 0, hp};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Line(5) = {5, 6}; Line(6) = {6, 7}; Line(7) = {7, 8}; Line(8) = {8, 5};
Line(9) = {9, 10}; Line(10) = {10, 11}; Line(11) = {11, 12}; Line(12) = {12, 9};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Curve Loop(2) = {5, 6, 7, 8}; Plane Surface(2) = {2};
Curve Loop(3) = {9, 10, 11, 12}; Plane Surface(3) = {3};
Physical Surface(1) = {1};
Physical Surface(2) = {2};
Physical Surface(3) = {3};
Physical Curve(0) = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};
Mesh.RandomSeed = 1;
