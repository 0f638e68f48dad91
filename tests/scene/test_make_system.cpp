// Tests for make_system: to be written.
