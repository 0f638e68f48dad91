// Tests for face_springs: to be written.
