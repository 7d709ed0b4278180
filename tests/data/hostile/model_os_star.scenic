# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# model_os_star (model_map): `model os` would import os's names (system) into the script.
# The payload runs at the top level, while the script compiles.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model os
status = system("touch '@CANARY@'")
if status != 0:
    raise RuntimeError(f"system answered {status}")

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
