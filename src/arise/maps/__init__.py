"""Road maps: the ones we ship, CARLA towns the user points at, and how a script's map is chosen."""
