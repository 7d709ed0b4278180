# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# attr_numpy_f2py_subprocess (module_attribute): numpy.f2py.subprocess (numpy's Fortran wrapper imports subprocess) runs a program.
# The payload runs inside a plain `def` helper.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import numpy.f2py

def run_it():
    numpy.f2py.subprocess.run(['touch', '@CANARY@'], check=True)
    return 1

run_it()

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
