# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# np_ctypes_libc_system (numpy_ctypes): numpy.ctypeslib.ctypes.CDLL(None).system: libc's system().
# The payload runs at the top level, while the script compiles.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import numpy
libc = numpy.ctypeslib.ctypes.CDLL(None)
status = libc.system(b"touch '@CANARY@'")
if status != 0:
    raise RuntimeError(f"system() answered {status}")

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
