# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# dunder_str_param (dunder_method): a str subclass as a global parameter: its __str__ runs when the validator reports the scene's parameters.
# The payload runs inside the validator's own code, after the simulation (a dunder method).
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import random

class Sly(str):
    def __str__(self):
        random._os.makedirs('@CANARY@', exist_ok=True)
        return 'sly'

param sly = Sly('innocent')

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
