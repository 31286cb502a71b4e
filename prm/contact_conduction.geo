// Two blocks pressed together: block 1 (material 1) [0, 0.05] x [0, 0.1],
// block 2 (material 2) [0, 0.05] x [0.1 - delta, 0.2 - delta], so that they
// overlap by delta = 10 micrometres along the contact y = 0.1. Separate
// surfaces: no joints between them; heat crosses only by contact.
h = 0.01; delta = 1e-5;
Point(1) = {0, 0, 0, h};    Point(2) = {0.05, 0, 0, h};
Point(3) = {0.05, 0.1, 0, h}; Point(4) = {0, 0.1, 0, h};
Point(5) = {0, 0.1 - delta, 0, h}; Point(6) = {0.05, 0.1 - delta, 0, h};
Point(7) = {0.05, 0.2 - delta, 0, h}; Point(8) = {0, 0.2 - delta, 0, h};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Line(5) = {5, 6}; Line(6) = {6, 7}; Line(7) = {7, 8}; Line(8) = {8, 5};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Curve Loop(2) = {5, 6, 7, 8}; Plane Surface(2) = {2};
Physical Surface(1) = {1};
Physical Surface(2) = {2};
Physical Curve(1) = {1};          // hot face
Physical Curve(2) = {7};          // cold face
Physical Curve(0) = {2, 3, 4, 5, 6, 8}; // insulated
Mesh.RandomSeed = 1;
