# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# attr_collections_sys_os_open (module_attribute): collections._sys.modules['os'].open creates a file, evaluated in a require.
# The payload runs inside a `require` / `terminate when` expression.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import collections

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
require collections._sys.modules['os'].open('@CANARY@', collections._sys.modules['os'].O_CREAT | collections._sys.modules['os'].O_WRONLY) >= 0
