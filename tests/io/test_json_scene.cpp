// Tests for json_scene: to be written.
