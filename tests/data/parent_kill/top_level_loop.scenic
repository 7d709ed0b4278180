# A script that will not stop: a top-level loop (it runs while the script compiles) that
# swallows every interrupt, the worker's own time-out included. Only a kill ends it.
param map = localPath('maps/arise_straight.xodr')
param carla_map = 'arise_straight'
model scenic.simulators.carla.model

spins = 0
while True:
    try:
        while True:
            spins += 1
    except BaseException:
        pass
