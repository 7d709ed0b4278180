# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# map_absolute_outside (model_map): `param map = '@PRIVATE@/secret_map.xodr'`: an absolute map path outside the script's folder, read as the map and directly.
# The payload runs at the top level, while the script compiles.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = '@PRIVATE@/secret_map.xodr'
param carla_map = Town
model scenic.simulators.carla.model
import numpy
stolen = numpy.fromfile(globalParameters.map, dtype=numpy.uint8).tobytes().decode(errors='replace')
if '<OpenDRIVE' not in stolen:
    raise RuntimeError('the map file holds: ' + stolen[:300])
direct = numpy.fromfile('@PRIVATE@/secret_map.xodr', dtype=numpy.uint8).tobytes().decode(errors='replace')
raise RuntimeError('read directly: ' + direct[:300])

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
