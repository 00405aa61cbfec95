"""What the scene means physically, once for every engine: its worlds (bodies, joints, collision
sets), the frame loop that drives an engine (evaluator, against the engine protocol), joint
outputs from body states, rotations, and the whole-scene checks and analyses."""
