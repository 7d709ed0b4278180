# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# np_ctypes_load_library_read (numpy_ctypes): numpy.ctypeslib.load_library loads libc; open()/read() of a secret into a C buffer.
# The payload runs inside a plain `def` helper.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import numpy

def steal():
    ct = numpy.ctypeslib.ctypes
    libc = numpy.ctypeslib.load_library('libc.so.6', '/lib/x86_64-linux-gnu/')
    handle = libc.open(b'@SECRET@', 0)
    if handle < 0:
        raise OSError(ct.get_errno(), 'open refused')
    buffer = ct.create_string_buffer(4096)
    count = libc.read(handle, buffer, 4096)
    raise RuntimeError('stolen: ' + buffer.raw[:max(count, 0)].decode())

steal()

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
