// Tests for load_scene: to be written.
