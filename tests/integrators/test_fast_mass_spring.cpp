// Tests for fast_mass_spring: to be written.
