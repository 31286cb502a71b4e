// Two square blocks 5 mm apart horizontally, separate bodies:
// material 1 (left), material 2 (right); boundary id 0 on all edges.
h = 0.01;
Point(1) = {0, 0, 0, h};    Point(2) = {0.1, 0, 0, h};
Point(3) = {0.1, 0.1, 0, h}; Point(4) = {0, 0.1, 0, h};
Point(5) = {0.105, 0.02, 0, h}; Point(6) = {0.205, 0.02, 0, h};
Point(7) = {0.205, 0.12, 0, h}; Point(8) = {0.105, 0.12, 0, h};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Line(5) = {5, 6}; Line(6) = {6, 7}; Line(7) = {7, 8}; Line(8) = {8, 5};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Curve Loop(2) = {5, 6, 7, 8}; Plane Surface(2) = {2};
Physical Surface(1) = {1};
Physical Surface(2) = {2};
Physical Curve(0) = {1, 2, 3, 4, 5, 6, 7, 8};
Mesh.MeshSizeMin = h; Mesh.MeshSizeMax = h;
Mesh.RandomSeed = 1;
