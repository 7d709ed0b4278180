# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# attr_dot_getattr (module_attribute): getattr taken as an attribute (roads.enum.bltns.getattr through Scenic's roads module), never called by its own name.
# The payload runs inside a `require` / `terminate when` expression.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import random
import scenic.domains.driving.roads as roads

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
require roads.enum.bltns.getattr(random, '_os').makedirs('@CANARY@', exist_ok=True) is None
