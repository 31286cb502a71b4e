// tmfdem tests: a square meshed far finer than gmsh can finish in 1 s
// (bad_input.gmsh_time_limit)
h = 0.0004;
Point(1) = {0, 0, 0, h};
Point(2) = {1, 0, 0, h};
Point(3) = {1, 1, 0, h};
Point(4) = {0, 1, 0, h};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Surface(2) = {1};
Physical Line(5) = {1, 2, 3, 4};
