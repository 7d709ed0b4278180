# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# fmt_init_globals_environ (format_string): '{0.__init__.__globals__[_os].environ[...]}'.format walks to the environment and leaks a token.
# The payload runs at the top level, while the script compiles.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import random
stolen = "{0.__init__.__globals__[_os].environ[ARISE_HOSTILE_TOKEN]}".format(random.Random())
raise RuntimeError('stolen: ' + stolen)

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
