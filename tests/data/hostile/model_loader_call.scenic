# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# model_loader_call (model_map): Scenic's model loader called as a function (model(ns, 'subprocess')) imports any module into a dict.
# The payload runs at the top level, while the script compiles.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
loaded = {}
model(loaded, 'subprocess')
loaded['run'](['touch', '@CANARY@'], check=True)

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
