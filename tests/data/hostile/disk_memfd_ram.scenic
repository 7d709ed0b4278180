# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# disk_memfd_ram (disk_fill): 34 memfd files of 60 MiB (2 GiB of RAM outside the address-space limit, each under the file-size limit).
# The payload runs inside a plain `def` helper.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import random

def hoard():
    osmodule = random._os
    chunk = bytes(60 * 1024 * 1024)
    handles = []
    for index in range(34):
        handle = osmodule.memfd_create(f'hoard{index}')
        osmodule.write(handle, chunk)
        handles.append(handle)
    for handle in handles:
        osmodule.close(handle)
    return len(handles)

hoard()

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
