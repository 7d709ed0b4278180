# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# attr_trimesh_util_sys (module_attribute): trimesh.util.sys.modules['os'] in a `require always` evaluated every simulation step.
# The payload runs inside a `require` / `terminate when` expression.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import trimesh

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
require always trimesh.util.sys.modules['os'].makedirs('@CANARY@', exist_ok=True) is None
