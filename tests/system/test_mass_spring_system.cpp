// Tests for mass_spring_system: to be written.
