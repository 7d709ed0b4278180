# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# alias_numpy_mtrand (module_attribute): numpy bound to another name (n = numpy) loses numpy's allow-list: n.random.mtrand.operator.attrgetter walks random._os.
# The payload runs inside a `behavior`, only once the simulation runs.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import random
import numpy
n = numpy

behavior Payload():
    n.random.mtrand.operator.attrgetter('_os.makedirs')(random)('@CANARY@', exist_ok=True)
    do FollowLaneBehavior(target_speed=8)

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior Payload()
