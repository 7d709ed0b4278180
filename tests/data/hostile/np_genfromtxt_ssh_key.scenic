# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# np_genfromtxt_ssh_key (numpy_io): numpy.genfromtxt reads an ssh key; it leaks as a global parameter of the scene.
# The payload runs at the top level, while the script compiles.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import numpy
param stolen = ' '.join(numpy.genfromtxt('@SSH_KEY@', dtype=str, delimiter='\t', comments=None))

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
