// The mesh of prm/thermal_shock_disc_cracking-3d.prm: the 13 x 1 mm disc of
// prm/thermal_shock_disc-3d.geo with tetrahedra of 0.4 mm at the rim (the
// ctest's mesh of the onset; 6127 tetrahedra, 0.8 mm inside).
h_rim = 0.4e-3;
Include "thermal_shock_disc-3d.geo";
