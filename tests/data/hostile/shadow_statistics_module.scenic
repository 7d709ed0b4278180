# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# shadow_statistics_module (module_shadowing): `import statistics` (an allowed name) finds statistics.py placed beside the script.
# The payload runs at the top level, while the script compiles.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import statistics
if getattr(statistics, 'SHADOW', None) != 'planted':
    raise RuntimeError('the real statistics module was imported, not the planted one')

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
