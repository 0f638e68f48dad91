// Tests for voronoi_masses: to be written.
