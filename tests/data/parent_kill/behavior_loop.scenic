# A script that will not stop: a behavior that never yields (it runs while the scene is
# simulated) and swallows every interrupt, the worker's own time-out included.
param map = localPath('maps/arise_straight.xodr')
param carla_map = 'arise_straight'
model scenic.simulators.carla.model

behavior Spin():
    spins = 0
    while True:
        try:
            while True:
                spins += 1
        except BaseException:
            pass
    take SetThrottleAction(0)

ego = new Car on road, with behavior Spin()
