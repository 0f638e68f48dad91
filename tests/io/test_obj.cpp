// Tests for obj: to be written.
