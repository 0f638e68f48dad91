// Tests for generators: to be written.
