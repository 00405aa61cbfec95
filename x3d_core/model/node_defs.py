"""Node type definitions: the X3D 4.0 interfaces x3drbp types, in a compact text form.

Drafted from the X3D Unified Object Model 4.0 and completed from ISO/IEC 19775-1
clause 37 where the UOM leaves a range out (mass (0,inf), errorCorrection [0,1],
joint angles [-pi,pi], ...). tests/test_uom.py checks names, types, access types,
defaults and UOM ranges against the UOM itself. Every other X3D 4.0 node type comes from
standard_nodes.py, generated from the UOM (x3d_core/model/uom.py); a type defined here wins.
An X3D 3.x file takes clause 37's 14 node types as the clause's text gives them instead
(clause37_nodes.py, x3d_core/model/editions.py), with the units and containerFields given here.

Line forms:
  node NAME : PARENTS @containerField       a concrete node type
  abstract NAME : PARENTS                   an abstract type (fields only where x3drbp needs them)
  FIELD TYPE ACCESS [RANGE] [u:UNIT] [<ACCEPTED|TYPES>] [= DEFAULT]
RANGE is an interval such as [0,1] or (0,inf), or one with a whole value besides
([0,inf)|-1,-1,-1: clause37_nodes.py's "[0,∞) or -1 -1 -1"); UNIT names the UNIT category the
field's value scales with; DEFAULT is in ClassicVRML encoding (omitted: the
type's empty value). Everything after '#' is a comment.
"""

DEFINITIONS = r"""
abstract X3DRigidJointNode : X3DNode
  body1 SFNode inputOutput <RigidBody>
  body2 SFNode inputOutput <RigidBody>
  forceOutput MFString inputOutput = "NONE"
  metadata SFNode inputOutput <X3DMetadataObject>
abstract X3DNBodyCollidableNode : X3DChildNode X3DBoundedObject
  bboxCenter SFVec3f initializeOnly u:length = 0 0 0
  bboxDisplay SFBool inputOutput = FALSE
  bboxSize SFVec3f initializeOnly u:length = -1 -1 -1
  enabled SFBool inputOutput = TRUE
  metadata SFNode inputOutput <X3DMetadataObject>
  rotation SFRotation inputOutput = 0 0 1 0
  translation SFVec3f inputOutput u:length = 0 0 0
  visible SFBool inputOutput = TRUE
abstract X3DNBodyCollisionSpaceNode : X3DNode X3DBoundedObject
  bboxCenter SFVec3f initializeOnly u:length = 0 0 0
  bboxDisplay SFBool inputOutput = FALSE
  bboxSize SFVec3f initializeOnly u:length = -1 -1 -1
  enabled SFBool inputOutput = TRUE
  metadata SFNode inputOutput <X3DMetadataObject>
  visible SFBool inputOutput = TRUE
node RigidBodyCollection : X3DChildNode X3DBoundedObject @children  # RigidBodyPhysics 2
  autoDisable SFBool inputOutput = FALSE
  bboxCenter SFVec3f initializeOnly u:length = 0 0 0
  bboxDisplay SFBool inputOutput = FALSE
  bboxSize SFVec3f initializeOnly u:length = -1 -1 -1
  bodies MFNode inputOutput <RigidBody>
  collider SFNode initializeOnly <CollisionCollection>
  constantForceMix SFFloat inputOutput [0,inf) = 0.0001
  contactSurfaceThickness SFFloat inputOutput [0,inf) u:length = 0
  disableAngularSpeed SFFloat inputOutput [0,inf) u:angular_rate = 0
  disableLinearSpeed SFFloat inputOutput [0,inf) u:speed = 0
  disableTime SFTime inputOutput [0,inf) = 0
  enabled SFBool inputOutput = TRUE
  errorCorrection SFFloat inputOutput [0,1] = 0.8
  gravity SFVec3f inputOutput u:acceleration = 0 -9.8 0
  iterations SFInt32 inputOutput [0,inf) = 10
  joints MFNode inputOutput <X3DRigidJointNode>
  maxCorrectionSpeed SFFloat inputOutput [-1,inf) u:speed = -1
  metadata SFNode inputOutput <X3DMetadataObject>
  preferAccuracy SFBool inputOutput = FALSE
  set_contacts MFNode inputOnly <Contact>
  visible SFBool inputOutput = TRUE
node RigidBody : X3DChildNode X3DBoundedObject @bodies  # RigidBodyPhysics 2
  angularDampingFactor SFFloat inputOutput [0,1] = 0.001
  angularVelocity SFVec3f inputOutput u:angular_rate = 0 0 0
  autoDamp SFBool inputOutput = FALSE
  autoDisable SFBool inputOutput = FALSE
  bboxCenter SFVec3f initializeOnly u:length = 0 0 0
  bboxDisplay SFBool inputOutput = FALSE
  bboxSize SFVec3f initializeOnly u:length = -1 -1 -1
  centerOfMass SFVec3f inputOutput u:length = 0 0 0
  disableAngularSpeed SFFloat inputOutput [0,inf) u:angular_rate = 0
  disableLinearSpeed SFFloat inputOutput [0,inf) u:speed = 0
  disableTime SFTime inputOutput [0,inf) = 0
  enabled SFBool inputOutput = TRUE
  finiteRotationAxis SFVec3f inputOutput [-1,1] = 0 1 0
  fixed SFBool inputOutput = FALSE
  forces MFVec3f inputOutput u:force
  geometry MFNode inputOutput <X3DNBodyCollidableNode>
  inertia SFMatrix3f inputOutput u:inertia = 1 0 0 0 1 0 0 0 1
  linearDampingFactor SFFloat inputOutput [0,1] = 0.001
  linearVelocity SFVec3f inputOutput u:speed = 0 0 0
  mass SFFloat inputOutput (0,inf) u:mass = 1
  massDensityModel SFNode inputOutput <Sphere|Box|Cone>
  metadata SFNode inputOutput <X3DMetadataObject>
  orientation SFRotation inputOutput = 0 0 1 0
  position SFVec3f inputOutput u:length = 0 0 0
  torques MFVec3f inputOutput u:torque
  useFiniteRotation SFBool inputOutput = FALSE
  useGlobalGravity SFBool inputOutput = TRUE
  visible SFBool inputOutput = TRUE
node BallJoint : X3DRigidJointNode @joints  # RigidBodyPhysics 2
  anchorPoint SFVec3f inputOutput u:length = 0 0 0
  body1 SFNode inputOutput <RigidBody>
  body1AnchorPoint SFVec3f outputOnly u:length
  body2 SFNode inputOutput <RigidBody>
  body2AnchorPoint SFVec3f outputOnly u:length
  forceOutput MFString inputOutput = "NONE"
  metadata SFNode inputOutput <X3DMetadataObject>
node SingleAxisHingeJoint : X3DRigidJointNode @joints  # RigidBodyPhysics 2
  anchorPoint SFVec3f inputOutput u:length = 0 0 0
  angle SFFloat outputOnly u:angle
  angleRate SFFloat outputOnly u:angular_rate
  axis SFVec3f inputOutput = 0 1 0
  body1 SFNode inputOutput <RigidBody>
  body1AnchorPoint SFVec3f outputOnly u:length
  body2 SFNode inputOutput <RigidBody>
  body2AnchorPoint SFVec3f outputOnly u:length
  forceOutput MFString inputOutput = "NONE"
  maxAngle SFFloat inputOutput [-3.141592653589793,3.141592653589793] u:angle = 3.141592653
  metadata SFNode inputOutput <X3DMetadataObject>
  minAngle SFFloat inputOutput [-3.141592653589793,3.141592653589793] u:angle = -3.141592653
  stopBounce SFFloat inputOutput [0,1] = 0
  stopErrorCorrection SFFloat inputOutput [0,1] = 0.8
node DoubleAxisHingeJoint : X3DRigidJointNode @joints  # RigidBodyPhysics 2
  anchorPoint SFVec3f inputOutput u:length = 0 0 0
  axis1 SFVec3f inputOutput = 1 0 0
  axis2 SFVec3f inputOutput = 0 1 0
  body1 SFNode inputOutput <RigidBody>
  body1AnchorPoint SFVec3f outputOnly u:length
  body1Axis SFVec3f outputOnly
  body2 SFNode inputOutput <RigidBody>
  body2AnchorPoint SFVec3f outputOnly u:length
  body2Axis SFVec3f outputOnly
  desiredAngularVelocity1 SFFloat inputOutput u:angular_rate = 0
  desiredAngularVelocity2 SFFloat inputOutput u:angular_rate = 0
  forceOutput MFString inputOutput = "NONE"
  hinge1Angle SFFloat outputOnly u:angle
  hinge1AngleRate SFFloat outputOnly u:angular_rate
  hinge2Angle SFFloat outputOnly u:angle
  hinge2AngleRate SFFloat outputOnly u:angular_rate
  maxAngle1 SFFloat inputOutput [-3.141592653589793,3.141592653589793] u:angle = 3.141592653
  maxTorque1 SFFloat inputOutput u:torque = 0
  maxTorque2 SFFloat inputOutput u:torque = 0
  metadata SFNode inputOutput <X3DMetadataObject>
  minAngle1 SFFloat inputOutput [-3.141592653589793,3.141592653589793] u:angle = -3.141592653
  stop1Bounce SFFloat inputOutput [0,1] = 0
  stop1ConstantForceMix SFFloat inputOutput [0,inf) = 0.001
  stop1ErrorCorrection SFFloat inputOutput [0,1] = 0.8
  suspensionErrorCorrection SFFloat inputOutput [0,1] = 0.8
  suspensionForce SFFloat inputOutput [0,inf) = 0
node SliderJoint : X3DRigidJointNode @joints  # RigidBodyPhysics 2
  axis SFVec3f inputOutput = 0 1 0
  body1 SFNode inputOutput <RigidBody>
  body2 SFNode inputOutput <RigidBody>
  forceOutput MFString inputOutput = "NONE"
  maxSeparation SFFloat inputOutput u:length = 1
  metadata SFNode inputOutput <X3DMetadataObject>
  minSeparation SFFloat inputOutput u:length = 0
  separation SFFloat outputOnly u:length
  separationRate SFFloat outputOnly u:speed
  sliderForce SFFloat inputOutput u:force = 0
  stopBounce SFFloat inputOutput [0,1] = 0
  stopErrorCorrection SFFloat inputOutput [0,1] = 1
node UniversalJoint : X3DRigidJointNode @joints  # RigidBodyPhysics 2
  anchorPoint SFVec3f inputOutput u:length = 0 0 0
  axis1 SFVec3f inputOutput = 1 0 0
  axis2 SFVec3f inputOutput = 0 1 0
  body1 SFNode inputOutput <RigidBody>
  body1AnchorPoint SFVec3f outputOnly u:length
  body1Axis SFVec3f outputOnly
  body2 SFNode inputOutput <RigidBody>
  body2AnchorPoint SFVec3f outputOnly u:length
  body2Axis SFVec3f outputOnly
  forceOutput MFString inputOutput = "NONE"
  metadata SFNode inputOutput <X3DMetadataObject>
  stop1Bounce SFFloat inputOutput [0,1] = 0
  stop1ErrorCorrection SFFloat inputOutput [0,1] = 0.8
  stop2Bounce SFFloat inputOutput [0,1] = 0
  stop2ErrorCorrection SFFloat inputOutput [0,1] = 0.8
node MotorJoint : X3DRigidJointNode @joints  # RigidBodyPhysics 2
  autoCalc SFBool initializeOnly = FALSE
  axis1Angle SFFloat inputOutput [-3.141592653589793,3.141592653589793] u:angle = 0
  axis1Torque SFFloat inputOutput u:torque = 0
  axis2Angle SFFloat inputOutput [-3.141592653589793,3.141592653589793] u:angle = 0
  axis2Torque SFFloat inputOutput u:torque = 0
  axis3Angle SFFloat inputOutput [-3.141592653589793,3.141592653589793] u:angle = 0
  axis3Torque SFFloat inputOutput u:torque = 0
  body1 SFNode inputOutput <RigidBody>
  body2 SFNode inputOutput <RigidBody>
  enabledAxes SFInt32 inputOutput [0,3] = 1
  forceOutput MFString inputOutput = "NONE"
  metadata SFNode inputOutput <X3DMetadataObject>
  motor1Angle SFFloat outputOnly u:angle
  motor1AngleRate SFFloat outputOnly u:angular_rate
  motor1Axis SFVec3f inputOutput = 1 0 0
  motor2Angle SFFloat outputOnly u:angle
  motor2AngleRate SFFloat outputOnly u:angular_rate
  motor2Axis SFVec3f inputOutput = 0 1 0
  motor3Angle SFFloat outputOnly u:angle
  motor3AngleRate SFFloat outputOnly u:angular_rate
  motor3Axis SFVec3f inputOutput = 0 0 1
  stop1Bounce SFFloat inputOutput [0,1] = 0
  stop1ErrorCorrection SFFloat inputOutput [0,1] = 0.8
  stop2Bounce SFFloat inputOutput [0,1] = 0
  stop2ErrorCorrection SFFloat inputOutput [0,1] = 0.8
  stop3Bounce SFFloat inputOutput [0,1] = 0
  stop3ErrorCorrection SFFloat inputOutput [0,1] = 0.8
node CollisionCollection : X3DChildNode X3DBoundedObject @collider  # RigidBodyPhysics 1
  appliedParameters MFString inputOutput = "BOUNCE"
  bboxCenter SFVec3f initializeOnly u:length = 0 0 0
  bboxDisplay SFBool inputOutput = FALSE
  bboxSize SFVec3f initializeOnly u:length = -1 -1 -1
  bounce SFFloat inputOutput [0,1] = 0
  collidables MFNode inputOutput <X3DNBodyCollisionSpaceNode|X3DNBodyCollidableNode>
  description SFString inputOutput
  enabled SFBool inputOutput = TRUE
  frictionCoefficients SFVec2f inputOutput [0,inf) = 0 0
  metadata SFNode inputOutput <X3DMetadataObject>
  minBounceSpeed SFFloat inputOutput [0,inf) u:speed = 0.1
  slipFactors SFVec2f inputOutput = 0 0
  softnessConstantForceMix SFFloat inputOutput [0,1] = 0.0001
  softnessErrorCorrection SFFloat inputOutput [0,1] = 0.8
  surfaceSpeed SFVec2f inputOutput u:speed = 0 0
  visible SFBool inputOutput = TRUE
node CollisionSpace : X3DNBodyCollisionSpaceNode @children  # RigidBodyPhysics 1
  bboxCenter SFVec3f initializeOnly u:length = 0 0 0
  bboxDisplay SFBool inputOutput = FALSE
  bboxSize SFVec3f initializeOnly u:length = -1 -1 -1
  collidables MFNode inputOutput <X3DNBodyCollisionSpaceNode|X3DNBodyCollidableNode>
  enabled SFBool inputOutput = TRUE
  metadata SFNode inputOutput <X3DMetadataObject>
  useGeometry SFBool inputOutput = FALSE
  visible SFBool inputOutput = TRUE
node CollisionSensor : X3DSensorNode @children  # RigidBodyPhysics 1
  collider SFNode inputOutput <CollisionCollection>
  contacts MFNode outputOnly <Contact>
  description SFString inputOutput
  enabled SFBool inputOutput = TRUE
  intersections MFNode outputOnly <X3DNBodyCollidableNode>
  isActive SFBool outputOnly
  metadata SFNode inputOutput <X3DMetadataObject>
node CollidableShape : X3DNBodyCollidableNode @children  # RigidBodyPhysics 1
  bboxCenter SFVec3f initializeOnly u:length = 0 0 0
  bboxDisplay SFBool inputOutput = FALSE
  bboxSize SFVec3f initializeOnly u:length = -1 -1 -1
  enabled SFBool inputOutput = TRUE
  metadata SFNode inputOutput <X3DMetadataObject>
  rotation SFRotation inputOutput = 0 0 1 0
  shape SFNode initializeOnly <Shape>
  translation SFVec3f inputOutput u:length = 0 0 0
  visible SFBool inputOutput = TRUE
node CollidableOffset : X3DNBodyCollidableNode @children  # RigidBodyPhysics 1
  bboxCenter SFVec3f initializeOnly u:length = 0 0 0
  bboxDisplay SFBool inputOutput = FALSE
  bboxSize SFVec3f initializeOnly u:length = -1 -1 -1
  collidable SFNode initializeOnly <X3DNBodyCollidableNode>
  enabled SFBool inputOutput = TRUE
  metadata SFNode inputOutput <X3DMetadataObject>
  rotation SFRotation inputOutput = 0 0 1 0
  translation SFVec3f inputOutput u:length = 0 0 0
  visible SFBool inputOutput = TRUE
node Contact : X3DNode @contacts  # RigidBodyPhysics 2
  appliedParameters MFString inputOutput = "BOUNCE"
  body1 SFNode inputOutput <RigidBody>
  body2 SFNode inputOutput <RigidBody>
  bounce SFFloat inputOutput [0,1] = 0
  contactNormal SFVec3f inputOutput = 0 1 0
  depth SFFloat inputOutput u:length = 0
  frictionCoefficients SFVec2f inputOutput [0,inf) = 0 0
  frictionDirection SFVec3f inputOutput = 0 1 0
  geometry1 SFNode inputOutput <X3DNBodyCollidableNode>
  geometry2 SFNode inputOutput <X3DNBodyCollidableNode>
  metadata SFNode inputOutput <X3DMetadataObject>
  minBounceSpeed SFFloat inputOutput [0,inf) u:speed = 0
  position SFVec3f inputOutput u:length = 0 0 0
  slipCoefficients SFVec2f inputOutput = 0 0
  softnessConstantForceMix SFFloat inputOutput [0,1] = 0.0001
  softnessErrorCorrection SFFloat inputOutput [0,1] = 0.8
  surfaceSpeed SFVec2f inputOutput u:speed = 0 0
node Group : X3DGroupingNode @children  # Grouping 1
  addChildren MFNode inputOnly <X3DChildNode>
  bboxCenter SFVec3f initializeOnly u:length = 0 0 0
  bboxDisplay SFBool inputOutput = FALSE
  bboxSize SFVec3f initializeOnly u:length = -1 -1 -1
  children MFNode inputOutput <X3DChildNode>
  metadata SFNode inputOutput <X3DMetadataObject>
  removeChildren MFNode inputOnly <X3DChildNode>
  visible SFBool inputOutput = TRUE
node Transform : X3DGroupingNode @children  # Grouping 1
  addChildren MFNode inputOnly <X3DChildNode>
  bboxCenter SFVec3f initializeOnly u:length = 0 0 0
  bboxDisplay SFBool inputOutput = FALSE
  bboxSize SFVec3f initializeOnly u:length = -1 -1 -1
  center SFVec3f inputOutput u:length = 0 0 0
  children MFNode inputOutput <X3DChildNode>
  metadata SFNode inputOutput <X3DMetadataObject>
  removeChildren MFNode inputOnly <X3DChildNode>
  rotation SFRotation inputOutput = 0 0 1 0
  scale SFVec3f inputOutput = 1 1 1
  scaleOrientation SFRotation inputOutput = 0 0 1 0
  translation SFVec3f inputOutput u:length = 0 0 0
  visible SFBool inputOutput = TRUE
node Shape : X3DShapeNode @children  # Shape 1
  appearance SFNode inputOutput <X3DAppearanceNode>
  bboxCenter SFVec3f initializeOnly u:length = 0 0 0
  bboxDisplay SFBool inputOutput = FALSE
  bboxSize SFVec3f initializeOnly u:length = -1 -1 -1
  castShadow SFBool inputOutput = TRUE
  geometry SFNode inputOutput <X3DGeometryNode>
  metadata SFNode inputOutput <X3DMetadataObject>
  visible SFBool inputOutput = TRUE
node Appearance : X3DAppearanceNode @appearance  # Shape 1
  acousticProperties SFNode inputOutput <AcousticProperties>
  alphaCutoff SFFloat inputOutput [0,1] = 0.5
  alphaMode SFString inputOutput = "AUTO"
  backMaterial SFNode inputOutput <X3DMaterialNode>
  fillProperties SFNode inputOutput <FillProperties>
  lineProperties SFNode inputOutput <LineProperties>
  material SFNode inputOutput <X3DMaterialNode>
  metadata SFNode inputOutput <X3DMetadataObject>
  pointProperties SFNode inputOutput <PointProperties>
  shaders MFNode inputOutput <X3DShaderNode>
  texture SFNode inputOutput <X3DTextureNode>
  textureTransform SFNode inputOutput <X3DTextureTransformNode>
node Material : X3DOneSidedMaterialNode @material  # Shape 1
  ambientIntensity SFFloat inputOutput [0,1] = 0.2
  ambientTexture SFNode inputOutput <X3DSingleTextureNode>
  ambientTextureMapping SFString inputOutput
  diffuseColor SFColor inputOutput [0,1] = 0.8 0.8 0.8
  diffuseTexture SFNode inputOutput <X3DSingleTextureNode>
  diffuseTextureMapping SFString inputOutput
  emissiveColor SFColor inputOutput [0,1] = 0 0 0
  emissiveTexture SFNode inputOutput <X3DSingleTextureNode>
  emissiveTextureMapping SFString inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  normalScale SFFloat inputOutput [0,inf) = 1
  normalTexture SFNode inputOutput <X3DSingleTextureNode>
  normalTextureMapping SFString inputOutput
  occlusionStrength SFFloat inputOutput [0,1] = 1
  occlusionTexture SFNode inputOutput <X3DSingleTextureNode>
  occlusionTextureMapping SFString inputOutput
  shininess SFFloat inputOutput [0,1] = 0.2
  shininessTexture SFNode inputOutput <X3DSingleTextureNode>
  shininessTextureMapping SFString inputOutput
  specularColor SFColor inputOutput [0,1] = 0 0 0
  specularTexture SFNode inputOutput <X3DSingleTextureNode>
  specularTextureMapping SFString inputOutput
  transparency SFFloat inputOutput [0,1] = 0
node Box : X3DGeometryNode @geometry  # Geometry3D 1
  metadata SFNode inputOutput <X3DMetadataObject>
  size SFVec3f initializeOnly (0,inf) u:length = 2 2 2
  solid SFBool initializeOnly = TRUE
node Sphere : X3DGeometryNode @geometry  # Geometry3D 1
  metadata SFNode inputOutput <X3DMetadataObject>
  radius SFFloat initializeOnly (0,inf) u:length = 1
  solid SFBool initializeOnly = TRUE
node Cone : X3DGeometryNode @geometry  # Geometry3D 1
  bottom SFBool inputOutput = TRUE
  bottomRadius SFFloat initializeOnly (0,inf) u:length = 1
  height SFFloat initializeOnly (0,inf) u:length = 2
  metadata SFNode inputOutput <X3DMetadataObject>
  side SFBool inputOutput = TRUE
  solid SFBool initializeOnly = TRUE
node Cylinder : X3DGeometryNode @geometry  # Geometry3D 1
  bottom SFBool inputOutput = TRUE
  height SFFloat initializeOnly (0,inf) u:length = 2
  metadata SFNode inputOutput <X3DMetadataObject>
  radius SFFloat initializeOnly (0,inf) u:length = 1
  side SFBool inputOutput = TRUE
  solid SFBool initializeOnly = TRUE
  top SFBool inputOutput = TRUE
node IndexedFaceSet : X3DComposedGeometryNode @geometry  # Geometry3D 2
  attrib MFNode inputOutput <X3DVertexAttributeNode>
  ccw SFBool initializeOnly = TRUE
  color SFNode inputOutput <X3DColorNode>
  colorIndex MFInt32 initializeOnly [-1,inf)
  colorPerVertex SFBool initializeOnly = TRUE
  convex SFBool initializeOnly = TRUE
  coord SFNode inputOutput <X3DCoordinateNode>
  coordIndex MFInt32 initializeOnly [-1,inf)
  creaseAngle SFFloat initializeOnly [0,inf) u:angle = 0
  fogCoord SFNode inputOutput <FogCoordinate>
  metadata SFNode inputOutput <X3DMetadataObject>
  normal SFNode inputOutput <X3DNormalNode>
  normalIndex MFInt32 initializeOnly [-1,inf)
  normalPerVertex SFBool initializeOnly = TRUE
  set_colorIndex MFInt32 inputOnly [-1,inf)
  set_coordIndex MFInt32 inputOnly [-1,inf)
  set_normalIndex MFInt32 inputOnly [-1,inf)
  set_texCoordIndex MFInt32 inputOnly [-1,inf)
  solid SFBool initializeOnly = TRUE
  texCoord SFNode inputOutput <X3DSingleTextureCoordinateNode|MultiTextureCoordinate>
  texCoordIndex MFInt32 initializeOnly [-1,inf)
node IndexedTriangleSet : X3DComposedGeometryNode @geometry  # Rendering 3
  attrib MFNode inputOutput <X3DVertexAttributeNode>
  ccw SFBool initializeOnly = TRUE
  color SFNode inputOutput <X3DColorNode>
  colorPerVertex SFBool initializeOnly = TRUE
  coord SFNode inputOutput <X3DCoordinateNode>
  fogCoord SFNode inputOutput <FogCoordinate>
  index MFInt32 initializeOnly [0,inf)
  metadata SFNode inputOutput <X3DMetadataObject>
  normal SFNode inputOutput <X3DNormalNode>
  normalPerVertex SFBool initializeOnly = TRUE
  set_index MFInt32 inputOnly [0,inf)
  solid SFBool initializeOnly = TRUE
  texCoord SFNode inputOutput <X3DSingleTextureCoordinateNode|MultiTextureCoordinate>
node TriangleSet : X3DComposedGeometryNode @geometry  # Rendering 3
  attrib MFNode inputOutput <X3DVertexAttributeNode>
  ccw SFBool initializeOnly = TRUE
  color SFNode inputOutput <X3DColorNode>
  colorPerVertex SFBool initializeOnly = TRUE
  coord SFNode inputOutput <X3DCoordinateNode>
  fogCoord SFNode inputOutput <FogCoordinate>
  metadata SFNode inputOutput <X3DMetadataObject>
  normal SFNode inputOutput <X3DNormalNode>
  normalPerVertex SFBool initializeOnly = TRUE
  solid SFBool initializeOnly = TRUE
  texCoord SFNode inputOutput <X3DSingleTextureCoordinateNode|MultiTextureCoordinate>
node Coordinate : X3DCoordinateNode @coord  # Rendering 1
  metadata SFNode inputOutput <X3DMetadataObject>
  point MFVec3f inputOutput u:length
node Normal : X3DNormalNode @normal  # Rendering 2
  metadata SFNode inputOutput <X3DMetadataObject>
  vector MFVec3f inputOutput [-1,1]
node Color : X3DColorNode @color  # Rendering 1
  color MFColor inputOutput [0,1]
  metadata SFNode inputOutput <X3DMetadataObject>
node TextureCoordinate : X3DSingleTextureCoordinateNode @texCoord  # Texturing 1
  mapping SFString inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  point MFVec2f inputOutput u:length
node ElevationGrid : X3DGeometryNode @geometry  # Geometry3D 3
  attrib MFNode inputOutput <X3DVertexAttributeNode>
  ccw SFBool initializeOnly = TRUE
  color SFNode inputOutput <X3DColorNode>
  colorPerVertex SFBool initializeOnly = TRUE
  creaseAngle SFFloat initializeOnly [0,inf) u:angle = 0
  fogCoord SFNode inputOutput <FogCoordinate>
  height MFFloat initializeOnly u:length
  metadata SFNode inputOutput <X3DMetadataObject>
  normal SFNode inputOutput <X3DNormalNode>
  normalPerVertex SFBool initializeOnly = TRUE
  set_height MFFloat inputOnly
  solid SFBool initializeOnly = TRUE
  texCoord SFNode inputOutput <X3DSingleTextureCoordinateNode>
  xDimension SFInt32 initializeOnly [0,inf) = 0
  xSpacing SFFloat initializeOnly (0,inf) u:length = 1.0
  zDimension SFInt32 initializeOnly [0,inf) = 0
  zSpacing SFFloat initializeOnly (0,inf) u:length = 1.0
node WorldInfo : X3DInfoNode @children  # Core 1
  info MFString inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  title SFString inputOutput
node Viewpoint : X3DViewpointNode @children  # Navigation 1
  bindTime SFTime outputOnly
  centerOfRotation SFVec3f inputOutput u:length = 0 0 0
  description SFString inputOutput
  farDistance SFFloat inputOutput = -1
  fieldOfView SFFloat inputOutput (0,3.1416) u:angle = 0.7854
  isBound SFBool outputOnly
  jump SFBool inputOutput = TRUE
  metadata SFNode inputOutput <X3DMetadataObject>
  navigationInfo SFNode inputOutput <NavigationInfo>
  nearDistance SFFloat inputOutput = -1
  orientation SFRotation inputOutput = 0 0 1 0
  position SFVec3f inputOutput u:length = 0 0 10
  retainUserOffsets SFBool inputOutput = FALSE
  set_bind SFBool inputOnly
  viewAll SFBool inputOutput = FALSE
node NavigationInfo : X3DBindableNode @children  # Navigation 1
  avatarSize MFFloat inputOutput [0,inf) u:length = 0.25 1.6 0.75
  bindTime SFTime outputOnly
  headlight SFBool inputOutput = TRUE
  isBound SFBool outputOnly
  metadata SFNode inputOutput <X3DMetadataObject>
  set_bind SFBool inputOnly
  speed SFFloat inputOutput [0,inf) u:speed = 1
  transitionComplete SFBool outputOnly
  transitionTime SFTime inputOutput [0,inf) = 1.0
  transitionType MFString inputOutput = "LINEAR"
  type MFString inputOutput = "EXAMINE" "ANY"
  visibilityLimit SFFloat inputOutput [0,inf) u:length = 0
node Background : X3DBackgroundNode @children  # EnvironmentalEffects 1
  backUrl MFString inputOutput
  bindTime SFTime outputOnly
  bottomUrl MFString inputOutput
  frontUrl MFString inputOutput
  groundAngle MFFloat inputOutput [0,1.5708] u:angle
  groundColor MFColor inputOutput [0,1]
  isBound SFBool outputOnly
  leftUrl MFString inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  rightUrl MFString inputOutput
  set_bind SFBool inputOnly
  skyAngle MFFloat inputOutput [0,3.1416] u:angle
  skyColor MFColor inputOutput [0,1] = 0 0 0
  topUrl MFString inputOutput
  transparency SFFloat inputOutput [0,1] = 0
node DirectionalLight : X3DLightNode @children  # Lighting 1
  ambientIntensity SFFloat inputOutput [0,1] = 0
  color SFColor inputOutput [0,1] = 1 1 1
  direction SFVec3f inputOutput = 0 0 -1
  global SFBool inputOutput = FALSE
  intensity SFFloat inputOutput [0,inf) = 1
  metadata SFNode inputOutput <X3DMetadataObject>
  on SFBool inputOutput = TRUE
  shadowIntensity SFFloat inputOutput [0,1] = 1
  shadows SFBool inputOutput = FALSE
node TimeSensor : X3DTimeDependentNode X3DSensorNode @children  # Time 1
  cycleInterval SFTime inputOutput [0,inf) = 1.0
  cycleTime SFTime outputOnly [0,inf)
  description SFString inputOutput
  elapsedTime SFTime outputOnly [0,inf)
  enabled SFBool inputOutput = TRUE
  fraction_changed SFFloat outputOnly
  isActive SFBool outputOnly
  isPaused SFBool outputOnly
  loop SFBool inputOutput = FALSE
  metadata SFNode inputOutput <X3DMetadataObject>
  pauseTime SFTime inputOutput = 0
  resumeTime SFTime inputOutput = 0
  startTime SFTime inputOutput = 0
  stopTime SFTime inputOutput = 0
  time SFTime outputOnly [0,inf)
node PositionInterpolator : X3DInterpolatorNode @children  # Interpolation 1
  key MFFloat inputOutput
  keyValue MFVec3f inputOutput u:length
  metadata SFNode inputOutput <X3DMetadataObject>
  set_fraction SFFloat inputOnly
  value_changed SFVec3f outputOnly
node OrientationInterpolator : X3DInterpolatorNode @children  # Interpolation 1
  key MFFloat inputOutput
  keyValue MFRotation inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  set_fraction SFFloat inputOnly
  value_changed SFRotation outputOnly
node Script : X3DScriptNode @children  # Scripting 1
  autoRefresh SFTime inputOutput [0,inf) = 0
  autoRefreshTimeLimit SFTime inputOutput [0,inf) = 3600
  description SFString inputOutput
  directOutput SFBool initializeOnly = FALSE
  load SFBool inputOutput = TRUE
  metadata SFNode inputOutput <X3DMetadataObject>
  mustEvaluate SFBool initializeOnly = FALSE
  sourceCode SFString inputOutput
  url MFString inputOutput
node MetadataSet : X3DNode X3DMetadataObject @value  # Core 1
  metadata SFNode inputOutput <X3DMetadataObject>
  name SFString inputOutput
  reference SFString inputOutput
  value MFNode inputOutput <X3DMetadataObject>
node MetadataString : X3DNode X3DMetadataObject @value  # Core 1
  metadata SFNode inputOutput <X3DMetadataObject>
  name SFString inputOutput
  reference SFString inputOutput
  value MFString inputOutput
node MetadataDouble : X3DNode X3DMetadataObject @value  # Core 1
  metadata SFNode inputOutput <X3DMetadataObject>
  name SFString inputOutput
  reference SFString inputOutput
  value MFDouble inputOutput
node MetadataBoolean : X3DNode X3DMetadataObject @value  # Core 1
  metadata SFNode inputOutput <X3DMetadataObject>
  name SFString inputOutput
  reference SFString inputOutput
  value MFBool inputOutput
node MetadataFloat : X3DNode X3DMetadataObject @value  # Core 1
  metadata SFNode inputOutput <X3DMetadataObject>
  name SFString inputOutput
  reference SFString inputOutput
  value MFFloat inputOutput
node MetadataInteger : X3DNode X3DMetadataObject @value  # Core 1
  metadata SFNode inputOutput <X3DMetadataObject>
  name SFString inputOutput
  reference SFString inputOutput
  value MFInt32 inputOutput
abstract X3DAppearanceChildNode : X3DNode
abstract X3DAppearanceNode : X3DNode
abstract X3DBackgroundNode : X3DBindableNode
abstract X3DBindableNode : X3DChildNode
abstract X3DBoundedObject
abstract X3DChildNode : X3DNode
abstract X3DColorNode : X3DGeometricPropertyNode
abstract X3DComposedGeometryNode : X3DGeometryNode
abstract X3DCoordinateNode : X3DGeometricPropertyNode
abstract X3DGeometricPropertyNode : X3DNode
abstract X3DGeometryNode : X3DNode
abstract X3DGroupingNode : X3DChildNode X3DBoundedObject
abstract X3DInfoNode : X3DChildNode
abstract X3DInterpolatorNode : X3DChildNode
abstract X3DLightNode : X3DChildNode
abstract X3DMaterialNode : X3DAppearanceChildNode
abstract X3DMetadataObject
abstract X3DNode
abstract X3DNormalNode : X3DGeometricPropertyNode
abstract X3DOneSidedMaterialNode : X3DMaterialNode
abstract X3DSensorNode : X3DChildNode
abstract X3DScriptNode : X3DChildNode X3DUrlObject
abstract X3DUrlObject
abstract X3DShapeNode : X3DChildNode X3DBoundedObject
abstract X3DSingleTextureCoordinateNode : X3DTextureCoordinateNode
abstract X3DTextureCoordinateNode : X3DGeometricPropertyNode
abstract X3DTimeDependentNode : X3DChildNode
abstract X3DViewpointNode : X3DBindableNode
"""
