# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# np_ctypes_pythonapi_run (numpy_ctypes): ctypes.pythonapi.PyRun_SimpleString runs Python source the gate never saw.
# The payload runs inside a `monitor`, only once the simulation runs.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import numpy

monitor Payload():
    status = numpy.ctypeslib.ctypes.pythonapi.PyRun_SimpleString(b"import os; os.mkdir('@CANARY@')")
    if status != 0:
        raise RuntimeError('PyRun_SimpleString failed')
    while True:
        wait

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
require monitor Payload()
