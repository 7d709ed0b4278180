# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# attr_getattr_alias (module_attribute): getattr under another name (fetch(random, '_os')) in a `terminate when` expression.
# The payload runs inside a `require` / `terminate when` expression.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import random
fetch = getattr

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
terminate when fetch(random, '_os').makedirs('@CANARY@', exist_ok=True) is not None
