# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# reexport_enum_builtins (module_attribute): the public name 'enum' of Scenic's roads module is the enum module, whose 'bltns' is builtins: its getattr reaches random._os.
# The payload runs at the top level, while the script compiles.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import random
from scenic.domains.driving.roads import enum

enum.bltns.getattr(random, '_os').makedirs('@CANARY@', exist_ok=True)

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
