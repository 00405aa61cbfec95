"""Clause 37's node signatures as its own text gives them (a V3 edition: X3D 3.x's names,
defaults and ranges), generated from ../shared/reference/clause37-rigid-body-physics.txt by
.venv/bin/python -m x3d_core.model.clause37 (do not edit): node_defs.py's text form, with no units
or containerFields (node_defs.py gives those). x3d_core/model/editions.py reads it for 3.x files.
"""

DEFINITIONS = r"""
abstract X3DNBodyCollidableNode : X3DChildNode X3DBoundedObject
  enabled SFBool inputOutput = TRUE
  metadata SFNode inputOutput <X3DMetadataObject>
  rotation SFRotation inputOutput [0,1] = 0 0 1 0
  translation SFVec3f inputOutput (-inf,inf)
  bboxCenter SFVec3f initializeOnly (-inf,inf)
  bboxSize SFVec3f initializeOnly [0,inf)|-1,-1,-1 = -1 -1 -1
abstract X3DNBodyCollisionSpaceNode : X3DNode X3DBoundedObject
  enabled SFBool inputOutput = TRUE
  metadata SFNode inputOutput <X3DMetadataObject>
  bboxCenter SFVec3f initializeOnly (-inf,inf)
  bboxSize SFVec3f initializeOnly [0,inf)|-1,-1,-1 = -1 -1 -1
abstract X3DRigidJointNode : X3DNode
  body1 SFNode inputOutput <RigidBody>
  body2 SFNode inputOutput <RigidBody>
  forceOutput MFString inputOutput = "NONE"
  metadata SFNode inputOutput <X3DMetadataObject>
node BallJoint : X3DRigidJointNode
  anchorPoint SFVec3f inputOutput
  body1 SFNode inputOutput <RigidBody>
  body2 SFNode inputOutput <RigidBody>
  forceOutput MFString inputOutput = "NONE"
  metadata SFNode inputOutput <X3DMetadataObject>
  body1AnchorPoint SFVec3f outputOnly
  body2AnchorPoint SFVec3f outputOnly
node CollidableOffset : X3DNBodyCollidableNode
  enabled SFBool inputOutput = TRUE
  metadata SFNode inputOutput <X3DMetadataObject>
  rotation SFRotation inputOutput [0,1] = 0 0 1 0
  translation SFVec3f inputOutput (-inf,inf)
  bboxCenter SFVec3f initializeOnly (-inf,inf)
  bboxSize SFVec3f initializeOnly [0,inf)|-1,-1,-1 = -1 -1 -1
  collidable SFNode initializeOnly <X3DNBodyCollidableNode>
node CollidableShape : X3DNBodyCollidableNode
  enabled SFBool inputOutput = TRUE
  metadata SFNode inputOutput <X3DMetadataObject>
  rotation SFRotation inputOutput [0,1] = 0 0 1 0
  translation SFVec3f inputOutput (-inf,inf)
  bboxCenter SFVec3f initializeOnly (-inf,inf)
  bboxSize SFVec3f initializeOnly [0,inf)|-1,-1,-1 = -1 -1 -1
  shape SFNode initializeOnly <Shape>
node CollisionCollection : X3DChildNode
  appliedParameters MFString inputOutput = "BOUNCE"
  bounce SFFloat inputOutput [0,1]
  collidables MFNode inputOutput <X3DNBodyCollisionSpaceNode|X3DNBodyCollidableNode>
  enabled SFBool inputOutput = TRUE
  frictionCoefficients SFVec2f inputOutput [0,inf)
  metadata SFNode inputOutput <X3DMetadataObject>
  minBounceSpeed SFFloat inputOutput [0,inf) = 0.1
  slipFactors SFVec2f inputOutput (-inf,inf)
  softnessConstantForceMix SFFloat inputOutput [0,1] = 0.0001
  softnessErrorCorrection SFFloat inputOutput [0,1] = 0.8
  surfaceSpeed SFVec2f inputOutput (-inf,inf)
node CollisionSensor : X3DSensorNode
  collider SFNode inputOutput <CollisionCollection>
  enabled SFBool inputOutput = TRUE
  metadata SFNode inputOutput <X3DMetadataObject>
  intersections MFNode outputOnly <X3DNBodyCollidableNode>
  contacts MFNode outputOnly <Contact>
  isActive SFBool outputOnly
node CollisionSpace : X3DNBodyCollisionSpaceNode
  collidables MFNode inputOutput <X3DNBodyCollisionSpaceNode|X3DNBodyCollidableNode>
  enabled SFBool inputOutput = TRUE
  metadata SFNode inputOutput <X3DMetadataObject>
  useGeometry SFBool inputOutput
  bboxCenter SFVec3f initializeOnly (-inf,inf)
  bboxSize SFVec3f initializeOnly [0,inf)|-1,-1,-1 = -1 -1 -1
node Contact : X3DNode
  appliedParameters MFString inputOutput = "BOUNCE"
  body1 SFNode inputOutput <RigidBody>
  body2 SFNode inputOutput <RigidBody>
  bounce SFFloat inputOutput [0,1]
  contactNormal SFVec3f inputOutput (-inf,inf) = 0 1 0
  depth SFFloat inputOutput (-inf,inf)
  frictionCoefficients SFVec2f inputOutput [0,inf)
  frictionDirection SFVec3f inputOutput (-inf,inf) = 0 1 0
  geometry1 SFNode inputOutput <X3DNBodyCollidableNode>
  geometry2 SFNode inputOutput <X3DNBodyCollidableNode>
  metadata SFNode inputOutput <X3DMetadataObject>
  minbounceSpeed SFFloat inputOutput [0,inf)
  position SFVec3f inputOutput (-inf,inf)
  slipCoefficients SFVec2f inputOutput (-inf,inf)
  softnessConstantForceMix SFFloat inputOutput [0,1] = 0.0001
  softnessErrorCorrection SFFloat inputOutput [0,1] = 0.8
  surfaceSpeed SFVec2f inputOutput (-inf,inf)
node DoubleAxisHingeJoint : X3DRigidJointNode
  anchorPoint SFVec3f inputOutput
  axis1 SFVec3f inputOutput
  axis2 SFVec3f inputOutput
  body1 SFNode inputOutput <RigidBody>
  body2 SFNode inputOutput <RigidBody>
  desiredAngularVelocity1 SFFloat inputOutput (-inf,inf)
  desiredAngularVelocity2 SFFloat inputOutput (-inf,inf)
  forceOutput MFString inputOutput = "NONE"
  maxAngle1 SFFloat inputOutput [-pi,pi] = 3.141592653589793
  maxTorque1 SFFloat inputOutput (-inf,inf)
  maxTorque2 SFFloat inputOutput (-inf,inf)
  metadata SFNode inputOutput <X3DMetadataObject>
  minAngle1 SFFloat inputOutput [-pi,pi] = -3.141592653589793
  stopBounce1 SFFloat inputOutput [0,1]
  stopConstantForceMix1 SFFloat inputOutput [0,inf) = 0.001
  stopErrorCorrection1 SFFloat inputOutput [0,1] = 0.8
  suspensionErrorCorrection SFFloat inputOutput [0,1] = 0.8
  suspensionForce SFFloat inputOutput [0,inf)
  body1AnchorPoint SFVec3f outputOnly
  body1Axis SFVec3f outputOnly
  body2AnchorPoint SFVec3f outputOnly
  body2Axis SFVec3f outputOnly
  hinge1Angle SFFloat outputOnly
  hinge1AngleRate SFFloat outputOnly
  hinge2Angle SFFloat outputOnly
  hinge2AngleRate SFFloat outputOnly
node MotorJoint : X3DRigidJointNode
  axis1Angle SFFloat inputOutput [-pi,pi]
  axis1Torque SFFloat inputOutput (-inf,inf)
  axis2Angle SFFloat inputOutput [-pi,pi]
  axis2Torque SFFloat inputOutput (-inf,inf)
  axis3Angle SFFloat inputOutput [-pi,pi]
  axis3Torque SFFloat inputOutput (-inf,inf)
  body1 SFNode inputOutput <RigidBody>
  body2 SFNode inputOutput <RigidBody>
  enabledAxes SFInt32 inputOutput [0,3] = 1
  forceOutput MFString inputOutput = "NONE"
  metadata SFNode inputOutput <X3DMetadataObject>
  motor1Axis SFVec3f inputOutput
  motor2Axis SFVec3f inputOutput
  motor3Axis SFVec3f inputOutput
  stop1Bounce SFFloat inputOutput [0,1]
  stop1ErrorCorrection SFFloat inputOutput [0,1] = 0.8
  stop2Bounce SFFloat inputOutput [0,1]
  stop2ErrorCorrection SFFloat inputOutput [0,1] = 0.8
  stop3Bounce SFFloat inputOutput [0,1]
  stop3ErrorCorrection SFFloat inputOutput [0,1] = 0.8
  motor1Angle SFFloat outputOnly
  motor1AngleRate SFFloat outputOnly
  motor2Angle SFFloat outputOnly
  motor2AngleRate SFFloat outputOnly
  motor3Angle SFFloat outputOnly
  motor3AngleRate SFFloat outputOnly
  autoCalc SFBool initializeOnly
node RigidBody : X3DNode
  angularDampingFactor SFFloat inputOutput [0,1] = 0.001
  angularVelocity SFVec3f inputOutput (-inf,inf)
  autoDamp SFBool inputOutput
  autoDisable SFBool inputOutput
  centerOfMass SFVec3f inputOutput (-inf,inf)
  disableAngularSpeed SFFloat inputOutput [0,inf)
  disableLinearSpeed SFFloat inputOutput [0,inf)
  disableTime SFFloat inputOutput [0,inf)
  enabled SFBool inputOutput = TRUE
  finiteRotationAxis SFVec3f inputOutput [-1,1]
  fixed SFBool inputOutput
  forces MFVec3f inputOutput
  geometry MFNode inputOutput <X3DNBodyCollidableNode>
  inertia SFMatrix3f inputOutput = 1 0 0 0 1 0 0 0 1
  linearDampingFactor SFFloat inputOutput [0,1] = 0.001
  linearVelocity SFVec3f inputOutput (-inf,inf)
  mass SFFloat inputOutput (0,inf) = 1
  massDensityModel SFNode inputOutput <Sphere|Box|Cone>
  metadata SFNode inputOutput <X3DMetadataObject>
  orientation SFRotation inputOutput [0,1] = 0 0 1 0
  position SFVec3f inputOutput (-inf,inf)
  torques MFVec3f inputOutput
  useFiniteRotation SFBool inputOutput
  useGlobalGravity SFBool inputOutput = TRUE
node RigidBodyCollection : X3DChildNode
  set_contacts MFNode inputOnly <Contact>
  autoDisable SFBool inputOutput
  bodies MFNode inputOutput <RigidBody>
  constantForceMix SFFloat inputOutput [0,inf) = 0.0001
  contactSurfaceThickness SFFloat inputOutput [0,inf)
  disableAngularSpeed SFFloat inputOutput [0,inf)
  disableLinearSpeed SFFloat inputOutput [0,inf)
  disableTime SFFloat inputOutput [0,inf)
  enabled SFBool inputOutput = TRUE
  errorCorrection SFFloat inputOutput [0,1] = 0.8
  gravity SFVec3f inputOutput = 0 -9.8 0
  iterations SFInt32 inputOutput [0,inf) = 10
  joints MFNode inputOutput <X3DRigidJointNode>
  maxCorrectionSpeed SFFloat inputOutput [0,inf)|-1 = -1
  metadata SFNode inputOutput <X3DMetadataObject>
  preferAccuracy SFBool inputOutput
  collider SFNode initializeOnly <CollisionCollection>
node SingleAxisHingeJoint : X3DRigidJointNode
  anchorPoint SFVec3f inputOutput
  axis SFVec3f inputOutput
  body1 SFNode inputOutput <RigidBody>
  body2 SFNode inputOutput <RigidBody>
  forceOutput MFString inputOutput = "NONE"
  maxAngle SFFloat inputOutput = 3.141592653589793
  metadata SFNode inputOutput <X3DMetadataObject>
  minAngle SFFloat inputOutput = -3.141592653589793
  stopBounce SFFloat inputOutput [0,1]
  stopErrorCorrection SFFloat inputOutput [0,1] = 0.8
  angle SFFloat outputOnly
  angleRate SFFloat outputOnly
  body1AnchorPoint SFVec3f outputOnly
  body2AnchorPoint SFVec3f outputOnly
node SliderJoint : X3DRigidJointNode
  axis SFVec3f inputOutput = 0 1 0
  body1 SFNode inputOutput <RigidBody>
  body2 SFNode inputOutput <RigidBody>
  forceOutput MFString inputOutput = "NONE"
  maxSeparation SFFloat inputOutput [0,inf) = 1
  metadata SFNode inputOutput <X3DMetadataObject>
  minSeparation SFFloat inputOutput [0,inf)
  stopBounce SFFloat inputOutput [0,1]
  stopErrorCorrection SFFloat inputOutput [0,1] = 1
  separation SFFloat outputOnly
  separationRate SFFloat outputOnly
node UniversalJoint : X3DRigidJointNode
  anchorPoint SFVec3f inputOutput
  axis1 SFVec3f inputOutput
  axis2 SFVec3f inputOutput
  body1 SFNode inputOutput <RigidBody>
  body2 SFNode inputOutput <RigidBody>
  metadata SFNode inputOutput <X3DMetadataObject>
  forceOutput MFString inputOutput = "NONE"
  stopBounce1 SFFloat inputOutput [0,1]
  stop1ErrorCorrection SFFloat inputOutput [0,1] = 0.8
  stop2Bounce SFFloat inputOutput [0,1]
  stop2ErrorCorrection SFFloat inputOutput [0,1] = 0.8
  body1AnchorPoint SFVec3f outputOnly
  body1Axis SFVec3f outputOnly
  body2AnchorPoint SFVec3f outputOnly
  body2Axis SFVec3f outputOnly
"""
