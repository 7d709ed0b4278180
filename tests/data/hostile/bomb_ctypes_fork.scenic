# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# bomb_ctypes_fork (bomb): fork() called through libc (ctypes) 20 times; each child makes the canary and exits.
# The payload runs at the top level, while the script compiles.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import numpy
libc = numpy.ctypeslib.ctypes.CDLL(None, use_errno=True)
for index in range(20):
    pid = libc.fork()
    if pid == 0:
        libc.close(libc.creat(b'@CANARY@', 0o644))
        libc._exit(0)
    if pid < 0:
        raise OSError(numpy.ctypeslib.ctypes.get_errno(), 'fork refused')

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
