# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# attr_dataclasses_inspect_os (module_attribute): dataclasses.inspect.os (a module imported by an allowed module) makes a directory.
# The payload runs inside a `behavior`, only once the simulation runs.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import dataclasses

behavior Payload():
    dataclasses.inspect.os.makedirs('@CANARY@', exist_ok=True)
    do FollowLaneBehavior(target_speed=8)

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior Payload()
