// Two cubes of 0.1 m that overlap by 10 mm along x (bad input for the
// discrete layer with contact: tests/CMakeLists.txt,
// bad_input.discrete_3d_initial_overlap): material 1 and 2 as in
// prm/two_blocks_collision-3d.geo.
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 0.1, 0.1, 0.1};
Box(2) = {0.09, 0.02, 0.01, 0.1, 0.1, 0.1};
Physical Volume(1) = {1};
Physical Volume(2) = {2};
Physical Surface(0) = {Boundary{ Volume{1}; }, Boundary{ Volume{2}; }};
Mesh.MeshSizeMin = 0.025;
Mesh.MeshSizeMax = 0.025;
Mesh.RandomSeed = 1;
