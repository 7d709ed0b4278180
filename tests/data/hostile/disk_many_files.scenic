# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# disk_many_files (disk_fill): 4096 files of 256 KiB (1 GiB in all) in the working folder, each under any per-file limit.
# The payload runs inside a `behavior`, only once the simulation runs.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import enum

behavior Payload():
    osmodule = enum.sys.modules['os']
    osmodule.makedirs('fill', exist_ok=True)
    chunk = bytes(256 * 1024)
    for index in range(4096):
        with enum.sys.modules['builtins'].open(f'fill/{index}.bin', 'wb') as handle:
            handle.write(chunk)
    for index in range(4096):
        osmodule.remove(f'fill/{index}.bin')
    do FollowLaneBehavior(target_speed=8)

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior Payload()
