# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# disk_big_file (disk_fill): one 1 GiB file in the working folder (removed afterwards, so the check would pass).
# The payload runs at the top level, while the script compiles.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import enum
handle = enum.sys.modules['builtins'].open('filler.bin', 'wb')
chunk = bytes(16 * 1024 * 1024)
for index in range(64):
    handle.write(chunk)
handle.close()
enum.sys.modules['os'].remove('filler.bin')

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
