# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# pickle_numpy_load_system (pickle): a hand-made pickle written with ndarray.tofile and loaded by numpy.load(allow_pickle=True) calls posix.system.
# The payload runs at the top level, while the script compiles.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import numpy
blob = b"cposix\nsystem\n(Vtouch '@CANARY@'\ntR."
numpy.frombuffer(blob, dtype=numpy.uint8).tofile('payload.pkl')
status = numpy.load('payload.pkl', allow_pickle=True)
if status != 0:
    raise RuntimeError(f"unpickled system() answered {status}")

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
