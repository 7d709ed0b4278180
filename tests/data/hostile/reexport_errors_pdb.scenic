# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# reexport_errors_pdb (module_attribute): the CARLA simulator module's public 'errors' is scenic.core.errors, whose 'pdb' hands out bdb: Bdb().run executes a string of code.
# The payload runs inside a plain `def` helper.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import scenic.simulators.carla.simulator as carla_sim

def debugger_run():
    carla_sim.errors.pdb.bdb.Bdb().run("import os; os.makedirs('@CANARY@', exist_ok=True)")
    return 1

param debugged = debugger_run()

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
