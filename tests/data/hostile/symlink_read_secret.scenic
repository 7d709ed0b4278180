# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# symlink_read_secret (symlink): a symlink beside the script (notes.txt -> the secret) read by the payload.
# The payload runs inside a plain `def` helper.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import numpy
NOTES = localPath('notes.txt')

def steal():
    data = numpy.fromfile(NOTES, dtype=numpy.uint8).tobytes().decode()
    raise RuntimeError('stolen: ' + data)

steal()

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
