# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# attr_scenic_namespace_builtins (module_attribute): Scenic's compiled name _Scenic_module_namespace is the script's globals: its '__builtins__' hands out getattr.
# The payload runs at the top level, while the script compiles.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import random
fetch = _Scenic_module_namespace['__builtins__']['getattr']
fetch(random, '_os').makedirs('@CANARY@', exist_ok=True)

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
