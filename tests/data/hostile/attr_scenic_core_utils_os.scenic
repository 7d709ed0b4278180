# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# attr_scenic_core_utils_os (module_attribute): scenic.core.utils.os (an allowed Scenic module) reaches os.system.
# The payload runs at the top level, while the script compiles.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import scenic.core.utils as helpers
status = helpers.os.system("touch '@CANARY@'")
if status != 0:
    raise RuntimeError(f"os.system answered {status}")

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
