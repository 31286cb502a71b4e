// tmfdem tests: a .geo file with a syntax error in line 3 (missing comma)
Point(1) = {0, 0, 0, 0.1};
Point(2) = {1, 0, 0 0.1};
Point(3) = {1, 1, 0, 0.1};
