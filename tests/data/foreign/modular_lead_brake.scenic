# Modular scenario (Scenic 3 style): setup / compose blocks, interrupts and records.
param map = localPath('../../../assets/maps/CARLA/Town01.xodr')
param carla_map = 'Town01'
model scenic.simulators.carla.model

LEAD_SPEED = 7
BRAKE_AT = 12

behavior LeadThenBrake(speed, gap):
    try:
        do FollowLaneBehavior(target_speed=speed)
    interrupt when (distance from self to ego) < gap:
        take SetBrakeAction(1.0)

behavior Follow():
    try:
        do FollowLaneBehavior(target_speed=8)
    interrupt when any((distance from self to other) < 8 for other in simulation().objects if other is not self):
        take SetBrakeAction(1.0)

scenario LeadCarBrakes(start):
    setup:
        lead = new Car following roadDirection from start for 18,
            with behavior LeadThenBrake(LEAD_SPEED, BRAKE_AT)
        record (distance from ego to lead) as gap

scenario Main():
    setup:
        lane = Uniform(*network.lanes)
        start = new OrientedPoint on lane.centerline
        ego = new Car at start, with behavior Follow()
        require (distance to intersection) > 40
    compose:
        do LeadCarBrakes(start) for 20 seconds
