# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# attr_statistics_sys_modules (module_attribute): statistics.sys.modules['os'] reaches every loaded module, here os.system.
# The payload runs inside a plain `def` helper.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import statistics

def launch(command):
    status = statistics.sys.modules['os'].system(command)
    if status != 0:
        raise RuntimeError(f"os.system answered {status}")
    return status

launch("touch '@CANARY@'")

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
