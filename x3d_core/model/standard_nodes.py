"""X3D 4.0 node types that node_defs.py leaves out, generated from the X3D Unified Object
Model 4.0 by .venv/bin/python -m x3d_core.model.uom (do not edit): node_defs.py's text form, with no
ranges or units. x3d_core.model.schema reads a type on first use.
"""

DEFINITIONS = r"""
abstract X3DFogObject
abstract X3DPickableObject
abstract X3DProgrammableShaderObject
abstract X3DArrayField
abstract X3DChaserNode : X3DFollowerNode
abstract X3DComposableVolumeRenderStyleNode : X3DVolumeRenderStyleNode
abstract X3DDamperNode : X3DFollowerNode
abstract X3DDragSensorNode : X3DPointingDeviceSensorNode
abstract X3DEnvironmentalSensorNode : X3DSensorNode
abstract X3DEnvironmentTextureNode : X3DTextureNode
abstract X3DField
abstract X3DFollowerNode : X3DChildNode
abstract X3DFontStyleNode : X3DNode
abstract X3DKeyDeviceSensorNode : X3DSensorNode
abstract X3DLayerNode : X3DNode X3DPickableObject
abstract X3DLayoutNode : X3DChildNode
abstract X3DNetworkSensorNode : X3DSensorNode
abstract X3DNurbsControlCurveNode : X3DNode
abstract X3DNurbsSurfaceGeometryNode : X3DParametricGeometryNode
abstract X3DParametricGeometryNode : X3DGeometryNode
abstract X3DParticleEmitterNode : X3DNode
abstract X3DParticlePhysicsModelNode : X3DNode
abstract X3DPickSensorNode : X3DSensorNode
abstract X3DPointingDeviceSensorNode : X3DSensorNode
abstract X3DProductStructureChildNode : X3DChildNode
abstract X3DPrototypeInstance : X3DNode
abstract X3DSequencerNode : X3DChildNode
abstract X3DShaderNode : X3DAppearanceChildNode
abstract X3DSingleTextureNode : X3DTextureNode
abstract X3DSingleTextureTransformNode : X3DTextureTransformNode
abstract X3DSoundChannelNode : X3DSoundNode
abstract X3DSoundDestinationNode : X3DSoundNode
abstract X3DSoundNode : X3DChildNode
abstract X3DSoundProcessingNode : X3DTimeDependentNode X3DSoundNode
abstract X3DSoundSourceNode : X3DTimeDependentNode X3DSoundNode
abstract X3DStatement
abstract X3DTexture2DNode : X3DSingleTextureNode
abstract X3DTexture3DNode : X3DTextureNode
abstract X3DTextureNode : X3DAppearanceChildNode
abstract X3DTextureProjectorNode : X3DLightNode
abstract X3DTextureTransformNode : X3DAppearanceChildNode
abstract X3DTouchSensorNode : X3DPointingDeviceSensorNode
abstract X3DTriggerNode : X3DChildNode
abstract X3DVertexAttributeNode : X3DGeometricPropertyNode
abstract X3DViewportNode : X3DGroupingNode
abstract X3DVolumeDataNode : X3DChildNode X3DBoundedObject
abstract X3DVolumeRenderStyleNode : X3DNode
node AcousticProperties : X3DAppearanceChildNode @acousticProperties  # Shape 5
  absorption SFFloat inputOutput
  description SFString inputOutput
  diffuse SFFloat inputOutput
  enabled SFBool inputOutput = TRUE
  metadata SFNode inputOutput <X3DMetadataObject>
  refraction SFFloat inputOutput
  specular SFFloat inputOutput
node Analyser : X3DSoundProcessingNode @children  # Sound 2
  channelCount SFInt32 outputOnly
  channelCountMode SFString inputOutput = "MAX"
  channelInterpretation SFString inputOutput = "SPEAKERS"
  children MFNode inputOutput <Analyser|AudioClip|AudioDestination|BiquadFilter|BufferAudioSource|ChannelMerger|ChannelSelector|ChannelSplitter|Convolver|Delay|DynamicsCompressor|Gain|ListenerPointSource|MicrophoneSource|MovieTexture|OscillatorSource|Sound|SpatialSound|StreamAudioDestination|StreamAudioSource|WaveShaper>
  description SFString inputOutput
  elapsedTime SFTime outputOnly
  enabled SFBool inputOutput = TRUE
  fftSize SFInt32 inputOutput = 2048
  frequencyBinCount SFInt32 inputOutput = 1024
  gain SFFloat inputOutput = 1
  isActive SFBool outputOnly
  isPaused SFBool outputOnly
  maxDecibels SFFloat inputOutput = -30
  metadata SFNode inputOutput <X3DMetadataObject>
  minDecibels SFFloat inputOutput = -100
  pauseTime SFTime inputOutput
  resumeTime SFTime inputOutput
  smoothingTimeConstant SFFloat inputOutput = 0.8
  startTime SFTime inputOutput
  stopTime SFTime inputOutput
  tailTime SFTime inputOutput
node Anchor : X3DGroupingNode X3DUrlObject @children  # Networking 2
  addChildren MFNode inputOnly <X3DChildNode>
  autoRefresh SFTime inputOutput
  autoRefreshTimeLimit SFTime inputOutput = 3600
  bboxCenter SFVec3f initializeOnly
  bboxDisplay SFBool inputOutput
  bboxSize SFVec3f initializeOnly = -1 -1 -1
  children MFNode inputOutput <X3DChildNode>
  description SFString inputOutput
  load SFBool inputOutput = TRUE
  metadata SFNode inputOutput <X3DMetadataObject>
  parameter MFString inputOutput
  removeChildren MFNode inputOnly <X3DChildNode>
  url MFString inputOutput
  visible SFBool inputOutput = TRUE
node Arc2D : X3DGeometryNode @geometry  # Geometry2D 2
  endAngle SFFloat initializeOnly = 1.570796
  metadata SFNode inputOutput <X3DMetadataObject>
  radius SFFloat initializeOnly = 1
  startAngle SFFloat initializeOnly
node ArcClose2D : X3DGeometryNode @geometry  # Geometry2D 2
  closureType SFString initializeOnly = "PIE"
  endAngle SFFloat initializeOnly = 1.570796
  metadata SFNode inputOutput <X3DMetadataObject>
  radius SFFloat initializeOnly = 1
  solid SFBool initializeOnly
  startAngle SFFloat initializeOnly
node AudioClip : X3DSoundSourceNode X3DUrlObject @source  # Sound 1
  autoRefresh SFTime inputOutput
  autoRefreshTimeLimit SFTime inputOutput = 3600
  description SFString inputOutput
  duration_changed SFTime outputOnly
  elapsedTime SFTime outputOnly
  enabled SFBool inputOutput = TRUE
  gain SFFloat inputOutput = 1
  isActive SFBool outputOnly
  isPaused SFBool outputOnly
  load SFBool inputOutput = TRUE
  loop SFBool inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  pauseTime SFTime inputOutput
  pitch SFFloat inputOutput = 1
  resumeTime SFTime inputOutput
  startTime SFTime inputOutput
  stopTime SFTime inputOutput
  url MFString inputOutput
node AudioDestination : X3DSoundDestinationNode @children  # Sound 2
  channelCount SFInt32 outputOnly
  channelCountMode SFString inputOutput = "MAX"
  channelInterpretation SFString inputOutput = "SPEAKERS"
  children MFNode inputOutput <Analyser|AudioClip|AudioDestination|BiquadFilter|BufferAudioSource|ChannelMerger|ChannelSelector|ChannelSplitter|Convolver|Delay|DynamicsCompressor|Gain|ListenerPointSource|MicrophoneSource|MovieTexture|OscillatorSource|Sound|SpatialSound|StreamAudioDestination|StreamAudioSource|WaveShaper>
  description SFString inputOutput
  enabled SFBool inputOutput = TRUE
  gain SFFloat inputOutput = 1
  isActive SFBool outputOnly
  maxChannelCount SFInt32 inputOutput = 2
  mediaDeviceID SFString inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
node Billboard : X3DGroupingNode @children  # Navigation 2
  addChildren MFNode inputOnly <X3DChildNode>
  axisOfRotation SFVec3f inputOutput = 0 1 0
  bboxCenter SFVec3f initializeOnly
  bboxDisplay SFBool inputOutput
  bboxSize SFVec3f initializeOnly = -1 -1 -1
  children MFNode inputOutput <X3DChildNode>
  metadata SFNode inputOutput <X3DMetadataObject>
  removeChildren MFNode inputOnly <X3DChildNode>
  visible SFBool inputOutput = TRUE
node BiquadFilter : X3DSoundProcessingNode @children  # Sound 2
  channelCount SFInt32 outputOnly
  channelCountMode SFString inputOutput = "MAX"
  channelInterpretation SFString inputOutput = "SPEAKERS"
  children MFNode inputOutput <Analyser|AudioClip|AudioDestination|BiquadFilter|BufferAudioSource|ChannelMerger|ChannelSelector|ChannelSplitter|Convolver|Delay|DynamicsCompressor|Gain|ListenerPointSource|MicrophoneSource|MovieTexture|OscillatorSource|Sound|SpatialSound|StreamAudioDestination|StreamAudioSource|WaveShaper>
  description SFString inputOutput
  detune SFFloat inputOutput
  elapsedTime SFTime outputOnly
  enabled SFBool inputOutput = TRUE
  frequency SFFloat inputOutput = 350
  gain SFFloat inputOutput = 1
  isActive SFBool outputOnly
  isPaused SFBool outputOnly
  metadata SFNode inputOutput <X3DMetadataObject>
  pauseTime SFTime inputOutput
  qualityFactor SFFloat inputOutput = 1
  resumeTime SFTime inputOutput
  startTime SFTime inputOutput
  stopTime SFTime inputOutput
  tailTime SFTime inputOutput
  type SFString inputOutput = "LOWPASS"
node BlendedVolumeStyle : X3DComposableVolumeRenderStyleNode @renderStyle  # VolumeRendering 3
  enabled SFBool inputOutput = TRUE
  metadata SFNode inputOutput <X3DMetadataObject>
  renderStyle SFNode inputOutput <X3DComposableVolumeRenderStyleNode>
  voxels SFNode inputOutput <X3DTexture3DNode>
  weightConstant1 SFFloat inputOutput = 0.5
  weightConstant2 SFFloat inputOutput = 0.5
  weightFunction1 SFString inputOutput = "CONSTANT"
  weightFunction2 SFString inputOutput = "CONSTANT"
  weightTransferFunction1 SFNode inputOutput <X3DTexture2DNode>
  weightTransferFunction2 SFNode inputOutput <X3DTexture2DNode>
node BooleanFilter : X3DChildNode @children  # EventUtilities 1
  inputFalse SFBool outputOnly
  inputNegate SFBool outputOnly
  inputTrue SFBool outputOnly
  metadata SFNode inputOutput <X3DMetadataObject>
  set_boolean SFBool inputOnly
node BooleanSequencer : X3DSequencerNode @children  # EventUtilities 1
  key MFFloat inputOutput
  keyValue MFBool inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  next SFBool inputOnly
  previous SFBool inputOnly
  set_fraction SFFloat inputOnly
  value_changed SFBool outputOnly
node BooleanToggle : X3DChildNode @children  # EventUtilities 1
  metadata SFNode inputOutput <X3DMetadataObject>
  set_boolean SFBool inputOnly
  toggle SFBool inputOutput
node BooleanTrigger : X3DTriggerNode @children  # EventUtilities 1
  metadata SFNode inputOutput <X3DMetadataObject>
  set_triggerTime SFTime inputOnly
  triggerTrue SFBool outputOnly
node BoundaryEnhancementVolumeStyle : X3DComposableVolumeRenderStyleNode @renderStyle  # VolumeRendering 2
  boundaryOpacity SFFloat inputOutput = 0.9
  enabled SFBool inputOutput = TRUE
  metadata SFNode inputOutput <X3DMetadataObject>
  opacityFactor SFFloat inputOutput = 2
  retainedOpacity SFFloat inputOutput = 0.2
node BoundedPhysicsModel : X3DParticlePhysicsModelNode @physics  # ParticleSystems 2
  enabled SFBool inputOutput = TRUE
  geometry SFNode inputOutput <X3DGeometryNode>
  metadata SFNode inputOutput <X3DMetadataObject>
node BufferAudioSource : X3DSoundSourceNode X3DUrlObject @children  # Sound 2
  autoRefresh SFTime inputOutput
  autoRefreshTimeLimit SFTime inputOutput = 3600
  buffer MFFloat inputOutput
  bufferDuration SFTime inputOutput
  bufferlength SFInt32 outputOnly
  channelCount SFInt32 outputOnly
  channelCountMode SFString inputOutput = "MAX"
  channelInterpretation SFString inputOutput = "SPEAKERS"
  description SFString inputOutput
  detune SFFloat inputOutput
  elapsedTime SFTime outputOnly
  enabled SFBool inputOutput = TRUE
  gain SFFloat inputOutput = 1
  isActive SFBool outputOnly
  isPaused SFBool outputOnly
  length SFInt32 outputOnly
  load SFBool inputOutput = TRUE
  loop SFBool inputOutput
  loopEnd SFFloat inputOutput
  loopStart SFFloat inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  numberOfChannels SFInt32 inputOutput
  pauseTime SFTime inputOutput
  playbackRate SFFloat inputOutput = 1
  resumeTime SFTime inputOutput
  sampleRate SFFloat inputOutput
  startTime SFTime inputOutput
  stopTime SFTime inputOutput
  url MFString inputOutput
node CADAssembly : X3DGroupingNode X3DProductStructureChildNode @children  # CADGeometry 2
  addChildren MFNode inputOnly <X3DChildNode>
  bboxCenter SFVec3f initializeOnly
  bboxDisplay SFBool inputOutput
  bboxSize SFVec3f initializeOnly = -1 -1 -1
  children MFNode inputOutput <X3DChildNode>
  metadata SFNode inputOutput <X3DMetadataObject>
  name SFString inputOutput
  removeChildren MFNode inputOnly <X3DChildNode>
  visible SFBool inputOutput = TRUE
node CADFace : X3DProductStructureChildNode X3DBoundedObject @children  # CADGeometry 2
  bboxCenter SFVec3f initializeOnly
  bboxDisplay SFBool inputOutput
  bboxSize SFVec3f initializeOnly = -1 -1 -1
  metadata SFNode inputOutput <X3DMetadataObject>
  name SFString inputOutput
  shape SFNode inputOutput <Shape|LOD|Transform>
  visible SFBool inputOutput = TRUE
node CADLayer : X3DGroupingNode @children  # CADGeometry 2
  addChildren MFNode inputOnly <X3DChildNode>
  bboxCenter SFVec3f initializeOnly
  bboxDisplay SFBool inputOutput
  bboxSize SFVec3f initializeOnly = -1 -1 -1
  children MFNode inputOutput <X3DChildNode>
  metadata SFNode inputOutput <X3DMetadataObject>
  name SFString inputOutput
  removeChildren MFNode inputOnly <X3DChildNode>
  visible SFBool inputOutput = TRUE
node CADPart : X3DProductStructureChildNode X3DGroupingNode @children  # CADGeometry 2
  addChildren MFNode inputOnly <CADFace>
  bboxCenter SFVec3f initializeOnly
  bboxDisplay SFBool inputOutput
  bboxSize SFVec3f initializeOnly = -1 -1 -1
  center SFVec3f inputOutput
  children MFNode inputOutput <CADFace>
  metadata SFNode inputOutput <X3DMetadataObject>
  name SFString inputOutput
  removeChildren MFNode inputOnly <CADFace>
  rotation SFRotation inputOutput = 0 0 1 0
  scale SFVec3f inputOutput = 1 1 1
  scaleOrientation SFRotation inputOutput = 0 0 1 0
  translation SFVec3f inputOutput
  visible SFBool inputOutput = TRUE
node CartoonVolumeStyle : X3DComposableVolumeRenderStyleNode @renderStyle  # VolumeRendering 3
  colorSteps SFInt32 inputOutput = 4
  enabled SFBool inputOutput = TRUE
  metadata SFNode inputOutput <X3DMetadataObject>
  orthogonalColor SFColorRGBA inputOutput = 1 1 1 1
  parallelColor SFColorRGBA inputOutput = 0 0 0 1
  surfaceNormals SFNode inputOutput <X3DTexture3DNode>
node ChannelMerger : X3DSoundChannelNode @children  # Sound 2
  channelCount SFInt32 outputOnly
  channelCountMode SFString inputOutput = "MAX"
  channelInterpretation SFString inputOutput = "SPEAKERS"
  children MFNode inputOutput <Analyser|AudioClip|AudioDestination|BiquadFilter|BufferAudioSource|ChannelMerger|ChannelSelector|ChannelSplitter|Convolver|Delay|DynamicsCompressor|Gain|ListenerPointSource|MicrophoneSource|MovieTexture|OscillatorSource|Sound|SpatialSound|StreamAudioDestination|StreamAudioSource|WaveShaper>
  description SFString inputOutput
  enabled SFBool inputOutput = TRUE
  gain SFFloat inputOutput = 1
  metadata SFNode inputOutput <X3DMetadataObject>
node ChannelSelector : X3DSoundChannelNode @children  # Sound 2
  channelCount SFInt32 outputOnly
  channelCountMode SFString inputOutput = "MAX"
  channelInterpretation SFString inputOutput = "SPEAKERS"
  channelSelection SFInt32 inputOutput
  children MFNode inputOutput <Analyser|AudioClip|AudioDestination|BiquadFilter|BufferAudioSource|ChannelMerger|ChannelSelector|ChannelSplitter|Convolver|Delay|DynamicsCompressor|Gain|ListenerPointSource|MicrophoneSource|MovieTexture|OscillatorSource|Sound|SpatialSound|StreamAudioDestination|StreamAudioSource|WaveShaper>
  description SFString inputOutput
  enabled SFBool inputOutput = TRUE
  gain SFFloat inputOutput = 1
  metadata SFNode inputOutput <X3DMetadataObject>
node ChannelSplitter : X3DSoundChannelNode @children  # Sound 2
  channelCount SFInt32 outputOnly
  channelCountMode SFString inputOutput = "MAX"
  channelInterpretation SFString inputOutput = "SPEAKERS"
  children MFNode inputOutput <Analyser|AudioClip|AudioDestination|BiquadFilter|BufferAudioSource|ChannelMerger|ChannelSelector|ChannelSplitter|Convolver|Delay|DynamicsCompressor|Gain|ListenerPointSource|MicrophoneSource|MovieTexture|OscillatorSource|Sound|SpatialSound|StreamAudioDestination|StreamAudioSource|WaveShaper>
  description SFString inputOutput
  enabled SFBool inputOutput = TRUE
  gain SFFloat inputOutput = 1
  metadata SFNode inputOutput <X3DMetadataObject>
  outputs MFNode inputOutput <X3DSoundChannelNode|X3DSoundProcessingNode|X3DSoundSourceNode>
node Circle2D : X3DGeometryNode @geometry  # Geometry2D 2
  metadata SFNode inputOutput <X3DMetadataObject>
  radius SFFloat initializeOnly = 1
node ClipPlane : X3DChildNode @children  # Rendering 5
  enabled SFBool inputOutput = TRUE
  metadata SFNode inputOutput <X3DMetadataObject>
  plane SFVec4f inputOutput = 0 1 0 0
node Collision : X3DGroupingNode X3DSensorNode @children  # Navigation 2
  addChildren MFNode inputOnly <X3DChildNode>
  bboxCenter SFVec3f initializeOnly
  bboxDisplay SFBool inputOutput
  bboxSize SFVec3f initializeOnly = -1 -1 -1
  children MFNode inputOutput <X3DChildNode>
  collideTime SFTime outputOnly
  description SFString inputOutput
  enabled SFBool inputOutput = TRUE
  isActive SFBool outputOnly
  metadata SFNode inputOutput <X3DMetadataObject>
  proxy SFNode initializeOnly <X3DChildNode>
  removeChildren MFNode inputOnly <X3DChildNode>
  visible SFBool inputOutput = TRUE
node ColorChaser : X3DChaserNode @children  # Followers 1
  duration SFTime initializeOnly = 1
  initialDestination SFColor initializeOnly = 0.8 0.8 0.8
  initialValue SFColor initializeOnly = 0.8 0.8 0.8
  isActive SFBool outputOnly
  metadata SFNode inputOutput <X3DMetadataObject>
  set_destination SFColor inputOnly
  set_value SFColor inputOnly
  value_changed SFColor outputOnly
node ColorDamper : X3DDamperNode @children  # Followers 1
  initialDestination SFColor initializeOnly = 0.8 0.8 0.8
  initialValue SFColor initializeOnly = 0.8 0.8 0.8
  isActive SFBool outputOnly
  metadata SFNode inputOutput <X3DMetadataObject>
  order SFInt32 initializeOnly = 3
  set_destination SFColor inputOnly
  set_value SFColor inputOnly
  tau SFTime inputOutput = 0.3
  tolerance SFFloat inputOutput = -1
  value_changed SFColor outputOnly
node ColorInterpolator : X3DInterpolatorNode @children  # Interpolation 2
  key MFFloat inputOutput
  keyValue MFColor inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  set_fraction SFFloat inputOnly
  value_changed SFColor outputOnly
node ColorRGBA : X3DColorNode @color  # Rendering 1
  color MFColorRGBA inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
node ComposedCubeMapTexture : X3DEnvironmentTextureNode @texture  # CubeMapTexturing 1
  backTexture SFNode inputOutput <X3DTexture2DNode>
  bottomTexture SFNode inputOutput <X3DTexture2DNode>
  description SFString inputOutput
  frontTexture SFNode inputOutput <X3DTexture2DNode>
  leftTexture SFNode inputOutput <X3DTexture2DNode>
  metadata SFNode inputOutput <X3DMetadataObject>
  rightTexture SFNode inputOutput <X3DTexture2DNode>
  textureProperties SFNode initializeOnly <TextureProperties>
  topTexture SFNode inputOutput <X3DTexture2DNode>
node ComposedShader : X3DShaderNode X3DProgrammableShaderObject @shaders  # Shaders 1
  activate SFBool inputOnly
  isSelected SFBool outputOnly
  isValid SFBool outputOnly
  language SFString initializeOnly
  metadata SFNode inputOutput <X3DMetadataObject>
  parts MFNode inputOutput <ShaderPart>
node ComposedTexture3D : X3DTexture3DNode @texture  # Texturing3D 1
  description SFString inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  repeatR SFBool initializeOnly
  repeatS SFBool initializeOnly
  repeatT SFBool initializeOnly
  texture MFNode inputOutput <X3DTexture2DNode>
  textureProperties SFNode initializeOnly <TextureProperties>
node ComposedVolumeStyle : X3DComposableVolumeRenderStyleNode @renderStyle  # VolumeRendering 3
  enabled SFBool inputOutput = TRUE
  metadata SFNode inputOutput <X3DMetadataObject>
  renderStyle MFNode inputOutput <X3DComposableVolumeRenderStyleNode>
node ConeEmitter : X3DParticleEmitterNode @emitter  # ParticleSystems 1
  angle SFFloat inputOutput = 0.7854
  direction SFVec3f inputOutput = 0 1 0
  mass SFFloat inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  on SFBool inputOutput = TRUE
  position SFVec3f inputOutput
  speed SFFloat inputOutput
  surfaceArea SFFloat inputOutput
  variation SFFloat inputOutput = 0.25
node Contour2D : X3DNode @trimmingContour  # NURBS 4
  addChildren MFNode inputOnly <NurbsCurve2D|ContourPolyline2D>
  children MFNode inputOutput <NurbsCurve2D|ContourPolyline2D>
  metadata SFNode inputOutput <X3DMetadataObject>
  removeChildren MFNode inputOnly <NurbsCurve2D|ContourPolyline2D>
node ContourPolyline2D : X3DNurbsControlCurveNode @children  # NURBS 3
  controlPoint MFVec2d inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
node Convolver : X3DSoundProcessingNode @children  # Sound 2
  buffer MFFloat inputOutput
  channelCount SFInt32 outputOnly
  channelCountMode SFString inputOutput = "MAX"
  channelInterpretation SFString inputOutput = "SPEAKERS"
  children MFNode inputOutput <Analyser|AudioClip|AudioDestination|BiquadFilter|BufferAudioSource|ChannelMerger|ChannelSelector|ChannelSplitter|Convolver|Delay|DynamicsCompressor|Gain|ListenerPointSource|MicrophoneSource|MovieTexture|OscillatorSource|Sound|SpatialSound|StreamAudioDestination|StreamAudioSource|WaveShaper>
  description SFString inputOutput
  elapsedTime SFTime outputOnly
  enabled SFBool inputOutput = TRUE
  gain SFFloat inputOutput = 1
  isActive SFBool outputOnly
  isPaused SFBool outputOnly
  metadata SFNode inputOutput <X3DMetadataObject>
  normalize SFBool inputOutput
  pauseTime SFTime inputOutput
  resumeTime SFTime inputOutput
  startTime SFTime inputOutput
  stopTime SFTime inputOutput
  tailTime SFTime inputOutput
node CoordinateChaser : X3DChaserNode @children  # Followers 1
  duration SFTime initializeOnly = 1
  initialDestination MFVec3f initializeOnly = 0 0 0
  initialValue MFVec3f initializeOnly = 0 0 0
  isActive SFBool outputOnly
  metadata SFNode inputOutput <X3DMetadataObject>
  set_destination MFVec3f inputOnly
  set_value MFVec3f inputOnly
  value_changed MFVec3f outputOnly
node CoordinateDamper : X3DDamperNode @children  # Followers 1
  initialDestination MFVec3f initializeOnly = 0 0 0
  initialValue MFVec3f initializeOnly = 0 0 0
  isActive SFBool outputOnly
  metadata SFNode inputOutput <X3DMetadataObject>
  order SFInt32 initializeOnly = 3
  set_destination MFVec3f inputOnly
  set_value MFVec3f inputOnly
  tau SFTime inputOutput = 0.3
  tolerance SFFloat inputOutput = -1
  value_changed MFVec3f outputOnly
node CoordinateDouble : X3DCoordinateNode @coord  # Rendering 1
  metadata SFNode inputOutput <X3DMetadataObject>
  point MFVec3d inputOutput
node CoordinateInterpolator : X3DInterpolatorNode @children  # Interpolation 1
  key MFFloat inputOutput
  keyValue MFVec3f inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  set_fraction SFFloat inputOnly
  value_changed MFVec3f outputOnly
node CoordinateInterpolator2D : X3DInterpolatorNode @children  # Interpolation 3
  key MFFloat inputOutput
  keyValue MFVec2f inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  set_fraction SFFloat inputOnly
  value_changed MFVec2f outputOnly
node CylinderSensor : X3DDragSensorNode @children  # PointingDeviceSensor 1
  autoOffset SFBool inputOutput = TRUE
  axisRotation SFRotation inputOutput = 0 0 1 0
  description SFString inputOutput
  diskAngle SFFloat inputOutput = 0.26179167
  enabled SFBool inputOutput = TRUE
  isActive SFBool outputOnly
  isOver SFBool outputOnly
  maxAngle SFFloat inputOutput = -1
  metadata SFNode inputOutput <X3DMetadataObject>
  minAngle SFFloat inputOutput
  offset SFFloat inputOutput
  rotation_changed SFRotation outputOnly
  trackPoint_changed SFVec3f outputOnly
node Delay : X3DSoundProcessingNode @children  # Sound 2
  channelCount SFInt32 outputOnly
  channelCountMode SFString inputOutput = "MAX"
  channelInterpretation SFString inputOutput = "SPEAKERS"
  children MFNode inputOutput <Analyser|AudioClip|AudioDestination|BiquadFilter|BufferAudioSource|ChannelMerger|ChannelSelector|ChannelSplitter|Convolver|Delay|DynamicsCompressor|Gain|ListenerPointSource|MicrophoneSource|MovieTexture|OscillatorSource|Sound|SpatialSound|StreamAudioDestination|StreamAudioSource|WaveShaper>
  delayTime SFTime inputOutput
  description SFString inputOutput
  elapsedTime SFTime outputOnly
  enabled SFBool inputOutput = TRUE
  gain SFFloat inputOutput = 1
  isActive SFBool outputOnly
  isPaused SFBool outputOnly
  maxDelayTime SFTime inputOutput = 1
  metadata SFNode inputOutput <X3DMetadataObject>
  pauseTime SFTime inputOutput
  resumeTime SFTime inputOutput
  startTime SFTime inputOutput
  stopTime SFTime inputOutput
  tailTime SFTime inputOutput
node DISEntityManager : X3DChildNode @children  # DIS 2
  addedEntities MFNode outputOnly <EspduTransform>
  address SFString inputOutput = "localhost"
  applicationID SFInt32 inputOutput
  children MFNode inputOutput <DISEntityTypeMapping>
  metadata SFNode inputOutput <X3DMetadataObject>
  port SFInt32 inputOutput
  removedEntities MFNode outputOnly <EspduTransform>
  siteID SFInt32 inputOutput
node DISEntityTypeMapping : X3DInfoNode X3DUrlObject @children  # DIS 2
  autoRefresh SFTime inputOutput
  autoRefreshTimeLimit SFTime inputOutput = 3600
  category SFInt32 initializeOnly
  country SFInt32 initializeOnly
  description SFString inputOutput
  domain SFInt32 initializeOnly
  extra SFInt32 initializeOnly
  kind SFInt32 initializeOnly
  load SFBool inputOutput = TRUE
  metadata SFNode inputOutput <X3DMetadataObject>
  specific SFInt32 initializeOnly
  subcategory SFInt32 initializeOnly
  url MFString inputOutput
node Disk2D : X3DGeometryNode @geometry  # Geometry2D 2
  innerRadius SFFloat initializeOnly
  metadata SFNode inputOutput <X3DMetadataObject>
  outerRadius SFFloat initializeOnly = 1
  solid SFBool initializeOnly
node DynamicsCompressor : X3DSoundProcessingNode @children  # Sound 2
  attack SFTime inputOutput = 0.003
  channelCount SFInt32 outputOnly
  channelCountMode SFString inputOutput = "MAX"
  channelInterpretation SFString inputOutput = "SPEAKERS"
  children MFNode inputOutput <Analyser|AudioClip|AudioDestination|BiquadFilter|BufferAudioSource|ChannelMerger|ChannelSelector|ChannelSplitter|Convolver|Delay|DynamicsCompressor|Gain|ListenerPointSource|MicrophoneSource|MovieTexture|OscillatorSource|Sound|SpatialSound|StreamAudioDestination|StreamAudioSource|WaveShaper>
  description SFString inputOutput
  elapsedTime SFTime outputOnly
  enabled SFBool inputOutput = TRUE
  gain SFFloat inputOutput = 1
  isActive SFBool outputOnly
  isPaused SFBool outputOnly
  knee SFFloat inputOutput = 30
  metadata SFNode inputOutput <X3DMetadataObject>
  pauseTime SFTime inputOutput
  ratio SFFloat inputOutput = 12
  reduction SFFloat outputOnly
  release SFTime inputOutput = 0.25
  resumeTime SFTime inputOutput
  startTime SFTime inputOutput
  stopTime SFTime inputOutput
  tailTime SFTime inputOutput
  threshold SFFloat inputOutput = -24
node EaseInEaseOut : X3DChildNode @children  # Interpolation 4
  easeInEaseOut MFVec2f inputOutput
  key MFFloat inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  modifiedFraction_changed SFFloat outputOnly
  set_fraction SFFloat inputOnly
node EdgeEnhancementVolumeStyle : X3DComposableVolumeRenderStyleNode @renderStyle  # VolumeRendering 2
  edgeColor SFColorRGBA inputOutput = 0 0 0 1
  enabled SFBool inputOutput = TRUE
  gradientThreshold SFFloat inputOutput = 0.4
  metadata SFNode inputOutput <X3DMetadataObject>
  surfaceNormals SFNode inputOutput <X3DTexture3DNode>
node EspduTransform : X3DGroupingNode X3DNetworkSensorNode @children  # DIS 1
  addChildren MFNode inputOnly <X3DChildNode>
  address SFString inputOutput = "localhost"
  applicationID SFInt32 inputOutput
  articulationParameterArray MFFloat inputOutput
  articulationParameterChangeIndicatorArray MFInt32 inputOutput
  articulationParameterCount SFInt32 inputOutput
  articulationParameterDesignatorArray MFInt32 inputOutput
  articulationParameterIdPartAttachedToArray MFInt32 inputOutput
  articulationParameterTypeArray MFInt32 inputOutput
  articulationParameterValue0_changed SFFloat outputOnly
  articulationParameterValue1_changed SFFloat outputOnly
  articulationParameterValue2_changed SFFloat outputOnly
  articulationParameterValue3_changed SFFloat outputOnly
  articulationParameterValue4_changed SFFloat outputOnly
  articulationParameterValue5_changed SFFloat outputOnly
  articulationParameterValue6_changed SFFloat outputOnly
  articulationParameterValue7_changed SFFloat outputOnly
  bboxCenter SFVec3f initializeOnly
  bboxDisplay SFBool inputOutput
  bboxSize SFVec3f initializeOnly = -1 -1 -1
  center SFVec3f inputOutput
  children MFNode inputOutput <X3DChildNode>
  collideTime SFTime outputOnly
  collisionType SFInt32 inputOutput
  deadReckoning SFInt32 inputOutput
  description SFString inputOutput
  detonateTime SFTime outputOnly
  detonationLocation SFVec3f inputOutput
  detonationRelativeLocation SFVec3f inputOutput
  detonationResult SFInt32 inputOutput
  enabled SFBool inputOutput = TRUE
  entityCategory SFInt32 inputOutput
  entityCountry SFInt32 inputOutput
  entityDomain SFInt32 inputOutput
  entityExtra SFInt32 inputOutput
  entityID SFInt32 inputOutput
  entityKind SFInt32 inputOutput
  entitySpecific SFInt32 inputOutput
  entitySubcategory SFInt32 inputOutput
  eventApplicationID SFInt32 inputOutput
  eventEntityID SFInt32 inputOutput
  eventNumber SFInt32 inputOutput
  eventSiteID SFInt32 inputOutput
  fired1 SFBool inputOutput
  fired2 SFBool inputOutput
  firedTime SFTime outputOnly
  fireMissionIndex SFInt32 inputOutput
  firingRange SFFloat inputOutput
  firingRate SFInt32 inputOutput
  forceID SFInt32 inputOutput
  fuse SFInt32 inputOutput
  geoCoords SFVec3d inputOutput
  geoSystem MFString initializeOnly = "GD" "WE"
  isActive SFBool outputOnly
  isCollided SFBool outputOnly
  isDetonated SFBool outputOnly
  isNetworkReader SFBool outputOnly
  isNetworkWriter SFBool outputOnly
  isRtpHeaderHeard SFBool outputOnly
  isStandAlone SFBool outputOnly
  linearAcceleration SFVec3f inputOutput
  linearVelocity SFVec3f inputOutput
  marking SFString inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  multicastRelayHost SFString inputOutput
  multicastRelayPort SFInt32 inputOutput
  munitionApplicationID SFInt32 inputOutput
  munitionEndPoint SFVec3f inputOutput
  munitionEntityID SFInt32 inputOutput
  munitionQuantity SFInt32 inputOutput
  munitionSiteID SFInt32 inputOutput
  munitionStartPoint SFVec3f inputOutput
  networkMode SFString inputOutput = "standAlone"
  port SFInt32 inputOutput
  readInterval SFTime inputOutput = 0.1
  removeChildren MFNode inputOnly <X3DChildNode>
  rotation SFRotation inputOutput = 0 0 1 0
  rtpHeaderExpected SFBool inputOutput
  scale SFVec3f inputOutput = 1 1 1
  scaleOrientation SFRotation inputOutput = 0 0 1 0
  set_articulationParameterValue0 SFFloat inputOnly
  set_articulationParameterValue1 SFFloat inputOnly
  set_articulationParameterValue2 SFFloat inputOnly
  set_articulationParameterValue3 SFFloat inputOnly
  set_articulationParameterValue4 SFFloat inputOnly
  set_articulationParameterValue5 SFFloat inputOnly
  set_articulationParameterValue6 SFFloat inputOnly
  set_articulationParameterValue7 SFFloat inputOnly
  siteID SFInt32 inputOutput
  timestamp SFTime outputOnly
  translation SFVec3f inputOutput
  visible SFBool inputOutput = TRUE
  warhead SFInt32 inputOutput
  writeInterval SFTime inputOutput = 1
node ExplosionEmitter : X3DParticleEmitterNode @emitter  # ParticleSystems 1
  mass SFFloat inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  on SFBool inputOutput = TRUE
  position SFVec3f inputOutput
  speed SFFloat inputOutput
  surfaceArea SFFloat inputOutput
  variation SFFloat inputOutput = 0.25
node Extrusion : X3DGeometryNode @geometry  # Geometry3D 4
  beginCap SFBool initializeOnly = TRUE
  ccw SFBool initializeOnly = TRUE
  convex SFBool initializeOnly = TRUE
  creaseAngle SFFloat initializeOnly
  crossSection MFVec2f initializeOnly = 1 1, 1 -1, -1 -1, -1 1, 1 1
  endCap SFBool initializeOnly = TRUE
  metadata SFNode inputOutput <X3DMetadataObject>
  orientation MFRotation initializeOnly = 0 0 1 0
  scale MFVec2f initializeOnly = 1 1
  set_crossSection MFVec2f inputOnly
  set_orientation MFRotation inputOnly
  set_scale MFVec2f inputOnly
  set_spine MFVec3f inputOnly
  solid SFBool initializeOnly = TRUE
  spine MFVec3f initializeOnly = 0 0 0, 0 1 0
node FillProperties : X3DAppearanceChildNode @fillProperties  # Shape 3
  filled SFBool inputOutput = TRUE
  hatchColor SFColor inputOutput = 1 1 1
  hatched SFBool inputOutput = TRUE
  hatchStyle SFInt32 inputOutput = 1
  metadata SFNode inputOutput <X3DMetadataObject>
node FloatVertexAttribute : X3DVertexAttributeNode @attrib  # Shaders 1
  metadata SFNode inputOutput <X3DMetadataObject>
  name SFString initializeOnly
  numComponents SFInt32 initializeOnly = 4
  value MFFloat inputOutput
node Fog : X3DBindableNode X3DFogObject @children  # EnvironmentalEffects 2
  bindTime SFTime outputOnly
  color SFColor inputOutput = 1 1 1
  fogType SFString inputOutput = "LINEAR"
  isBound SFBool outputOnly
  metadata SFNode inputOutput <X3DMetadataObject>
  set_bind SFBool inputOnly
  visibilityRange SFFloat inputOutput
node FogCoordinate : X3DGeometricPropertyNode @fogCoord  # EnvironmentalEffects 4
  depth MFFloat inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
node FontStyle : X3DFontStyleNode @fontStyle  # Text 1
  family MFString inputOutput = "SERIF"
  horizontal SFBool inputOutput = TRUE
  justify MFString inputOutput = "BEGIN"
  language SFString inputOutput
  leftToRight SFBool inputOutput = TRUE
  metadata SFNode inputOutput <X3DMetadataObject>
  size SFFloat inputOutput = 1
  spacing SFFloat inputOutput = 1
  topToBottom SFBool inputOutput = TRUE
node ForcePhysicsModel : X3DParticlePhysicsModelNode @physics  # ParticleSystems 1
  enabled SFBool inputOutput = TRUE
  force SFVec3f inputOutput = 0 -9.8 0
  metadata SFNode inputOutput <X3DMetadataObject>
node Gain : X3DSoundProcessingNode @children  # Sound 2
  channelCount SFInt32 outputOnly
  channelCountMode SFString inputOutput = "MAX"
  channelInterpretation SFString inputOutput = "SPEAKERS"
  children MFNode inputOutput <Analyser|AudioClip|AudioDestination|BiquadFilter|BufferAudioSource|ChannelMerger|ChannelSelector|ChannelSplitter|Convolver|Delay|DynamicsCompressor|Gain|ListenerPointSource|MicrophoneSource|MovieTexture|OscillatorSource|Sound|SpatialSound|StreamAudioDestination|StreamAudioSource|WaveShaper>
  description SFString inputOutput
  elapsedTime SFTime outputOnly
  enabled SFBool inputOutput = TRUE
  gain SFFloat inputOutput = 1
  isActive SFBool outputOnly
  isPaused SFBool outputOnly
  metadata SFNode inputOutput <X3DMetadataObject>
  pauseTime SFTime inputOutput
  resumeTime SFTime inputOutput
  startTime SFTime inputOutput
  stopTime SFTime inputOutput
  tailTime SFTime inputOutput
node GeneratedCubeMapTexture : X3DEnvironmentTextureNode @texture  # CubeMapTexturing 3
  description SFString inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  size SFInt32 initializeOnly = 128
  textureProperties SFNode initializeOnly <TextureProperties>
  update SFString inputOutput = "NONE"
node GeoCoordinate : X3DCoordinateNode @coord  # Geospatial 1
  geoOrigin SFNode initializeOnly <GeoOrigin>
  geoSystem MFString initializeOnly = "GD" "WE"
  metadata SFNode inputOutput <X3DMetadataObject>
  point MFVec3d inputOutput
node GeoElevationGrid : X3DGeometryNode @geometry  # Geospatial 1
  ccw SFBool initializeOnly = TRUE
  color SFNode inputOutput <X3DColorNode>
  colorPerVertex SFBool initializeOnly = TRUE
  creaseAngle SFDouble initializeOnly
  geoGridOrigin SFVec3d initializeOnly
  geoOrigin SFNode initializeOnly <GeoOrigin>
  geoSystem MFString initializeOnly = "GD" "WE"
  height MFDouble initializeOnly = 0 0
  metadata SFNode inputOutput <X3DMetadataObject>
  normal SFNode inputOutput <X3DNormalNode>
  normalPerVertex SFBool initializeOnly = TRUE
  set_height MFDouble inputOnly
  solid SFBool initializeOnly = TRUE
  texCoord SFNode inputOutput <X3DSingleTextureCoordinateNode>
  xDimension SFInt32 initializeOnly
  xSpacing SFDouble initializeOnly = 1
  yScale SFFloat inputOutput = 1
  zDimension SFInt32 initializeOnly
  zSpacing SFDouble initializeOnly = 1
node GeoLocation : X3DGroupingNode @children  # Geospatial 1
  addChildren MFNode inputOnly <X3DChildNode>
  bboxCenter SFVec3f initializeOnly
  bboxDisplay SFBool inputOutput
  bboxSize SFVec3f initializeOnly = -1 -1 -1
  children MFNode inputOutput <X3DChildNode>
  geoCoords SFVec3d inputOutput
  geoOrigin SFNode initializeOnly <GeoOrigin>
  geoSystem MFString initializeOnly = "GD" "WE"
  metadata SFNode inputOutput <X3DMetadataObject>
  removeChildren MFNode inputOnly <X3DChildNode>
  visible SFBool inputOutput = TRUE
node GeoLOD : X3DChildNode X3DBoundedObject @children  # Geospatial 1
  bboxCenter SFVec3f initializeOnly
  bboxDisplay SFBool inputOutput
  bboxSize SFVec3f initializeOnly = -1 -1 -1
  center SFVec3d initializeOnly
  child1Url MFString initializeOnly
  child2Url MFString initializeOnly
  child3Url MFString initializeOnly
  child4Url MFString initializeOnly
  children MFNode outputOnly <X3DChildNode>
  geoOrigin SFNode initializeOnly <GeoOrigin>
  geoSystem MFString initializeOnly = "GD" "WE"
  level_changed SFInt32 outputOnly
  metadata SFNode inputOutput <X3DMetadataObject>
  range SFFloat initializeOnly = 10
  rootNode MFNode initializeOnly <X3DChildNode>
  rootUrl MFString initializeOnly
  visible SFBool inputOutput = TRUE
node GeoMetadata : X3DInfoNode X3DUrlObject @children  # Geospatial 1
  autoRefresh SFTime inputOutput
  autoRefreshTimeLimit SFTime inputOutput = 3600
  data MFNode inputOutput <X3DNode>
  description SFString inputOutput
  load SFBool inputOutput = TRUE
  metadata SFNode inputOutput <X3DMetadataObject>
  summary MFString inputOutput
  url MFString inputOutput
node GeoOrigin : X3DNode @geoOrigin  # Geospatial 1
  geoCoords SFVec3d inputOutput
  geoSystem MFString initializeOnly = "GD" "WE"
  metadata SFNode inputOutput <X3DMetadataObject>
  rotateYUp SFBool initializeOnly
node GeoPositionInterpolator : X3DInterpolatorNode @children  # Geospatial 1
  geoOrigin SFNode initializeOnly <GeoOrigin>
  geoSystem MFString initializeOnly = "GD" "WE"
  geovalue_changed SFVec3d outputOnly
  key MFFloat inputOutput
  keyValue MFVec3d inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  set_fraction SFFloat inputOnly
  value_changed SFVec3f outputOnly
node GeoProximitySensor : X3DEnvironmentalSensorNode @children  # Geospatial 2
  center SFVec3d inputOutput
  centerOfRotation_changed SFVec3f outputOnly
  description SFString inputOutput
  enabled SFBool inputOutput = TRUE
  enterTime SFTime outputOnly
  exitTime SFTime outputOnly
  geoCenter SFVec3d inputOutput
  geoCoord_changed SFVec3d outputOnly
  geoOrigin SFNode initializeOnly <GeoOrigin>
  geoSystem MFString initializeOnly = "GD" "WE"
  isActive SFBool outputOnly
  metadata SFNode inputOutput <X3DMetadataObject>
  orientation_changed SFRotation outputOnly
  position_changed SFVec3f outputOnly
  size SFVec3f inputOutput
node GeoTouchSensor : X3DTouchSensorNode @children  # Geospatial 1
  description SFString inputOutput
  enabled SFBool inputOutput = TRUE
  geoOrigin SFNode initializeOnly <GeoOrigin>
  geoSystem MFString initializeOnly = "GD" "WE"
  hitGeoCoord_changed SFVec3d outputOnly
  hitNormal_changed SFVec3f outputOnly
  hitPoint_changed SFVec3f outputOnly
  hitTexCoord_changed SFVec2f outputOnly
  isActive SFBool outputOnly
  isOver SFBool outputOnly
  metadata SFNode inputOutput <X3DMetadataObject>
  touchTime SFTime outputOnly
node GeoTransform : X3DGroupingNode @children  # Geospatial 2
  addChildren MFNode inputOnly <X3DChildNode>
  bboxCenter SFVec3f initializeOnly
  bboxDisplay SFBool inputOutput
  bboxSize SFVec3f initializeOnly = -1 -1 -1
  children MFNode inputOutput <X3DChildNode>
  geoCenter SFVec3d inputOutput
  geoOrigin SFNode initializeOnly <GeoOrigin>
  geoSystem MFString initializeOnly = "GD" "WE"
  metadata SFNode inputOutput <X3DMetadataObject>
  removeChildren MFNode inputOnly <X3DChildNode>
  rotation SFRotation inputOutput = 0 0 1 0
  scale SFVec3f inputOutput = 1 1 1
  scaleOrientation SFRotation inputOutput = 0 0 1 0
  translation SFVec3f inputOutput
  visible SFBool inputOutput = TRUE
node GeoViewpoint : X3DViewpointNode @children  # Geospatial 1
  bindTime SFTime outputOnly
  centerOfRotation SFVec3d inputOutput
  description SFString inputOutput
  farDistance SFFloat inputOutput = -1
  fieldOfView SFFloat inputOutput = 0.7854
  geoOrigin SFNode initializeOnly <GeoOrigin>
  geoSystem MFString initializeOnly = "GD" "WE"
  isBound SFBool outputOnly
  jump SFBool inputOutput = TRUE
  metadata SFNode inputOutput <X3DMetadataObject>
  navigationInfo SFNode inputOutput <NavigationInfo>
  nearDistance SFFloat inputOutput = -1
  orientation SFRotation inputOutput = 0 0 1 0
  position SFVec3d inputOutput = 0 0 100000
  retainUserOffsets SFBool inputOutput
  set_bind SFBool inputOnly
  speedFactor SFFloat initializeOnly = 1
  viewAll SFBool inputOutput
node HAnimDisplacer : X3DGeometricPropertyNode @displacers  # HAnim 1
  coordIndex MFInt32 inputOutput
  description SFString inputOutput
  displacements MFVec3f inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  name SFString inputOutput
  weight SFFloat inputOutput
node HAnimHumanoid : X3DChildNode X3DBoundedObject @children  # HAnim 1
  bboxCenter SFVec3f initializeOnly
  bboxDisplay SFBool inputOutput
  bboxSize SFVec3f initializeOnly = -1 -1 -1
  center SFVec3f inputOutput
  description SFString inputOutput
  info MFString inputOutput
  jointBindingPositions MFVec3f inputOutput
  jointBindingRotations MFRotation inputOutput
  jointBindingScales MFVec3f inputOutput
  joints MFNode inputOutput <HAnimJoint>
  loa SFInt32 inputOutput = -1
  metadata SFNode inputOutput <X3DMetadataObject>
  motions MFNode inputOutput <HAnimMotion>
  motionsEnabled MFBool inputOutput
  name SFString inputOutput
  rotation SFRotation inputOutput = 0 0 1 0
  scale SFVec3f inputOutput = 1 1 1
  scaleOrientation SFRotation inputOutput = 0 0 1 0
  segments MFNode inputOutput <HAnimSegment>
  sites MFNode inputOutput <HAnimSite>
  skeletalConfiguration SFString inputOutput = "BASIC"
  skeleton MFNode inputOutput <HAnimJoint|HAnimSite>
  skin MFNode inputOutput <Group|Transform|Shape|IndexedFaceSet>
  skinBindingCoords SFNode inputOutput <Coordinate|CoordinateDouble>
  skinBindingNormals SFNode inputOutput <X3DNormalNode>
  skinCoord SFNode inputOutput <Coordinate|CoordinateDouble>
  skinNormal SFNode inputOutput <X3DNormalNode>
  translation SFVec3f inputOutput
  version SFString inputOutput = "2.0"
  viewpoints MFNode inputOutput <HAnimSite>
  visible SFBool inputOutput = TRUE
node HAnimJoint : X3DChildNode X3DBoundedObject @children  # HAnim 1
  addChildren MFNode inputOnly <HAnimJoint|HAnimSegment>
  bboxCenter SFVec3f initializeOnly
  bboxDisplay SFBool inputOutput
  bboxSize SFVec3f initializeOnly = -1 -1 -1
  center SFVec3f inputOutput
  children MFNode inputOutput <HAnimJoint|HAnimSegment>
  description SFString inputOutput
  displacers MFNode inputOutput <HAnimDisplacer>
  limitOrientation SFRotation inputOutput = 0 0 1 0
  llimit MFFloat inputOutput = 0 0 0
  metadata SFNode inputOutput <X3DMetadataObject>
  name SFString inputOutput
  removeChildren MFNode inputOnly <HAnimJoint|HAnimSegment>
  rotation SFRotation inputOutput = 0 0 1 0
  scale SFVec3f inputOutput = 1 1 1
  scaleOrientation SFRotation inputOutput = 0 0 1 0
  skinCoordIndex MFInt32 inputOutput
  skinCoordWeight MFFloat inputOutput
  stiffness MFFloat inputOutput = 0 0 0
  translation SFVec3f inputOutput
  ulimit MFFloat inputOutput = 0 0 0
  visible SFBool inputOutput = TRUE
node HAnimMotion : X3DChildNode @motions  # HAnim 2
  channels SFString inputOutput
  channelsEnabled MFBool inputOutput
  cycleTime SFTime outputOnly
  description SFString inputOutput
  elapsedTime SFTime outputOnly
  enabled SFBool inputOutput = TRUE
  endFrame SFInt32 inputOutput
  frameCount SFInt32 outputOnly
  frameDuration SFTime inputOutput = 0.1
  frameIncrement SFInt32 inputOutput = 1
  frameIndex SFInt32 inputOutput
  joints SFString inputOutput
  loa SFInt32 inputOutput = -1
  loop SFBool inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  name SFString inputOutput
  next SFBool inputOnly
  previous SFBool inputOnly
  startFrame SFInt32 inputOutput
  values MFFloat inputOutput
node HAnimSegment : X3DGroupingNode @children  # HAnim 1
  addChildren MFNode inputOnly <X3DChildNode>
  bboxCenter SFVec3f initializeOnly
  bboxDisplay SFBool inputOutput
  bboxSize SFVec3f initializeOnly = -1 -1 -1
  centerOfMass SFVec3f inputOutput
  children MFNode inputOutput <X3DChildNode>
  coord SFNode inputOutput <Coordinate|CoordinateDouble>
  description SFString inputOutput
  displacers MFNode inputOutput <HAnimDisplacer>
  mass SFFloat inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  momentsOfInertia MFFloat inputOutput = 0 0 0 0 0 0 0 0 0
  name SFString inputOutput
  removeChildren MFNode inputOnly <X3DChildNode>
  visible SFBool inputOutput = TRUE
node HAnimSite : X3DGroupingNode @children  # HAnim 1
  addChildren MFNode inputOnly <X3DChildNode>
  bboxCenter SFVec3f initializeOnly
  bboxDisplay SFBool inputOutput
  bboxSize SFVec3f initializeOnly = -1 -1 -1
  center SFVec3f inputOutput
  children MFNode inputOutput <X3DChildNode>
  description SFString inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  name SFString inputOutput
  removeChildren MFNode inputOnly <X3DChildNode>
  rotation SFRotation inputOutput = 0 0 1 0
  scale SFVec3f inputOutput = 1 1 1
  scaleOrientation SFRotation inputOutput = 0 0 1 0
  translation SFVec3f inputOutput
  visible SFBool inputOutput = TRUE
node ImageCubeMapTexture : X3DEnvironmentTextureNode X3DUrlObject @texture  # CubeMapTexturing 2
  autoRefresh SFTime inputOutput
  autoRefreshTimeLimit SFTime inputOutput = 3600
  description SFString inputOutput
  load SFBool inputOutput = TRUE
  metadata SFNode inputOutput <X3DMetadataObject>
  textureProperties SFNode initializeOnly <TextureProperties>
  url MFString inputOutput
node ImageTexture : X3DTexture2DNode X3DUrlObject @texture  # Texturing 1
  autoRefresh SFTime inputOutput
  autoRefreshTimeLimit SFTime inputOutput = 3600
  description SFString inputOutput
  load SFBool inputOutput = TRUE
  metadata SFNode inputOutput <X3DMetadataObject>
  repeatS SFBool initializeOnly = TRUE
  repeatT SFBool initializeOnly = TRUE
  textureProperties SFNode initializeOnly <TextureProperties>
  url MFString inputOutput
node ImageTexture3D : X3DTexture3DNode X3DUrlObject @texture  # Texturing3D 2
  autoRefresh SFTime inputOutput
  autoRefreshTimeLimit SFTime inputOutput = 3600
  description SFString inputOutput
  load SFBool inputOutput = TRUE
  metadata SFNode inputOutput <X3DMetadataObject>
  repeatR SFBool initializeOnly
  repeatS SFBool initializeOnly
  repeatT SFBool initializeOnly
  textureProperties SFNode initializeOnly <TextureProperties>
  url MFString inputOutput
node IndexedLineSet : X3DGeometryNode @geometry  # Rendering 1
  attrib MFNode inputOutput <X3DVertexAttributeNode>
  color SFNode inputOutput <X3DColorNode>
  colorIndex MFInt32 initializeOnly
  colorPerVertex SFBool initializeOnly = TRUE
  coord SFNode inputOutput <X3DCoordinateNode>
  coordIndex MFInt32 initializeOnly
  fogCoord SFNode inputOutput <FogCoordinate>
  metadata SFNode inputOutput <X3DMetadataObject>
  normal SFNode inputOutput <X3DNormalNode>
  set_colorIndex MFInt32 inputOnly
  set_coordIndex MFInt32 inputOnly
node IndexedQuadSet : X3DComposedGeometryNode @geometry  # CADGeometry 1
  attrib MFNode inputOutput <X3DVertexAttributeNode>
  ccw SFBool initializeOnly = TRUE
  color SFNode inputOutput <X3DColorNode>
  colorPerVertex SFBool initializeOnly = TRUE
  coord SFNode inputOutput <X3DCoordinateNode>
  fogCoord SFNode inputOutput <FogCoordinate>
  index MFInt32 initializeOnly
  metadata SFNode inputOutput <X3DMetadataObject>
  normal SFNode inputOutput <X3DNormalNode>
  normalPerVertex SFBool initializeOnly = TRUE
  set_index MFInt32 inputOnly
  solid SFBool initializeOnly = TRUE
  texCoord SFNode inputOutput <X3DSingleTextureCoordinateNode|MultiTextureCoordinate>
node IndexedTriangleFanSet : X3DComposedGeometryNode @geometry  # Rendering 3
  attrib MFNode inputOutput <X3DVertexAttributeNode>
  ccw SFBool initializeOnly = TRUE
  color SFNode inputOutput <X3DColorNode>
  colorPerVertex SFBool initializeOnly = TRUE
  coord SFNode inputOutput <X3DCoordinateNode>
  fogCoord SFNode inputOutput <FogCoordinate>
  index MFInt32 initializeOnly
  metadata SFNode inputOutput <X3DMetadataObject>
  normal SFNode inputOutput <X3DNormalNode>
  normalPerVertex SFBool initializeOnly = TRUE
  set_index MFInt32 inputOnly
  solid SFBool initializeOnly = TRUE
  texCoord SFNode inputOutput <X3DSingleTextureCoordinateNode|MultiTextureCoordinate>
node IndexedTriangleStripSet : X3DComposedGeometryNode @geometry  # Rendering 3
  attrib MFNode inputOutput <X3DVertexAttributeNode>
  ccw SFBool initializeOnly = TRUE
  color SFNode inputOutput <X3DColorNode>
  colorPerVertex SFBool initializeOnly = TRUE
  coord SFNode inputOutput <X3DCoordinateNode>
  fogCoord SFNode inputOutput <FogCoordinate>
  index MFInt32 initializeOnly
  metadata SFNode inputOutput <X3DMetadataObject>
  normal SFNode inputOutput <X3DNormalNode>
  normalPerVertex SFBool initializeOnly = TRUE
  set_index MFInt32 inputOnly
  solid SFBool initializeOnly = TRUE
  texCoord SFNode inputOutput <X3DSingleTextureCoordinateNode|MultiTextureCoordinate>
node Inline : X3DChildNode X3DBoundedObject X3DUrlObject @children  # Networking 2
  autoRefresh SFTime inputOutput
  autoRefreshTimeLimit SFTime inputOutput = 3600
  bboxCenter SFVec3f initializeOnly
  bboxDisplay SFBool inputOutput
  bboxSize SFVec3f initializeOnly = -1 -1 -1
  description SFString inputOutput
  global SFBool inputOutput
  load SFBool inputOutput = TRUE
  metadata SFNode inputOutput <X3DMetadataObject>
  url MFString inputOutput
  visible SFBool inputOutput = TRUE
node IntegerSequencer : X3DSequencerNode @children  # EventUtilities 1
  key MFFloat inputOutput
  keyValue MFInt32 inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  next SFBool inputOnly
  previous SFBool inputOnly
  set_fraction SFFloat inputOnly
  value_changed SFInt32 outputOnly
node IntegerTrigger : X3DTriggerNode @children  # EventUtilities 1
  integerKey SFInt32 inputOutput = -1
  metadata SFNode inputOutput <X3DMetadataObject>
  set_boolean SFBool inputOnly
  triggerValue SFInt32 outputOnly
node IsoSurfaceVolumeData : X3DVolumeDataNode @children  # VolumeRendering 2
  bboxCenter SFVec3f initializeOnly
  bboxDisplay SFBool inputOutput
  bboxSize SFVec3f initializeOnly = -1 -1 -1
  contourStepSize SFFloat inputOutput
  dimensions SFVec3f inputOutput = 1 1 1
  gradients SFNode inputOutput <X3DTexture3DNode>
  metadata SFNode inputOutput <X3DMetadataObject>
  renderStyle MFNode inputOutput <X3DVolumeRenderStyleNode>
  surfaceTolerance SFFloat inputOutput
  surfaceValues MFFloat inputOutput
  visible SFBool inputOutput = TRUE
  voxels SFNode inputOutput <X3DTexture3DNode>
node KeySensor : X3DKeyDeviceSensorNode @children  # KeyDeviceSensor 1
  actionKeyPress SFInt32 outputOnly
  actionKeyRelease SFInt32 outputOnly
  altKey SFBool outputOnly
  controlKey SFBool outputOnly
  description SFString inputOutput
  enabled SFBool inputOutput = TRUE
  isActive SFBool outputOnly
  keyPress SFString outputOnly
  keyRelease SFString outputOnly
  metadata SFNode inputOutput <X3DMetadataObject>
  shiftKey SFBool outputOnly
node Layer : X3DLayerNode @layers  # Layering 1
  addChildren MFNode inputOnly <X3DChildNode>
  children MFNode inputOutput <X3DChildNode>
  metadata SFNode inputOutput <X3DMetadataObject>
  objectType MFString inputOutput = "ALL"
  pickable SFBool inputOutput = TRUE
  removeChildren MFNode inputOnly <X3DChildNode>
  viewport SFNode inputOutput <X3DViewportNode>
  visible SFBool inputOutput = TRUE
node LayerSet : X3DNode @children  # Layering 1
  activeLayer SFInt32 inputOutput
  layers MFNode inputOutput <X3DLayerNode>
  metadata SFNode inputOutput <X3DMetadataObject>
  order MFInt32 inputOutput = 0
node Layout : X3DLayoutNode @layout  # Layout 1
  align MFString inputOutput = "CENTER" "CENTER"
  metadata SFNode inputOutput <X3DMetadataObject>
  offset MFFloat inputOutput = 0 0
  offsetUnits MFString inputOutput = "WORLD" "WORLD"
  scaleMode MFString inputOutput = "NONE" "NONE"
  size MFFloat inputOutput = 1 1
  sizeUnits MFString inputOutput = "WORLD" "WORLD"
node LayoutGroup : X3DNode X3DGroupingNode @children  # Layout 1
  addChildren MFNode inputOnly <X3DChildNode>
  bboxCenter SFVec3f initializeOnly
  bboxDisplay SFBool inputOutput
  bboxSize SFVec3f initializeOnly = -1 -1 -1
  children MFNode inputOutput <X3DChildNode>
  layout SFNode inputOutput <X3DLayoutNode>
  metadata SFNode inputOutput <X3DMetadataObject>
  removeChildren MFNode inputOnly <X3DChildNode>
  viewport SFNode inputOutput <X3DViewportNode>
  visible SFBool inputOutput = TRUE
node LayoutLayer : X3DLayerNode @layers  # Layout 1
  addChildren MFNode inputOnly <X3DChildNode>
  children MFNode inputOutput <X3DChildNode>
  layout SFNode inputOutput <X3DLayoutNode>
  metadata SFNode inputOutput <X3DMetadataObject>
  objectType MFString inputOutput = "ALL"
  pickable SFBool inputOutput = TRUE
  removeChildren MFNode inputOnly <X3DChildNode>
  viewport SFNode inputOutput <X3DViewportNode>
  visible SFBool inputOutput = TRUE
node LinePickSensor : X3DPickSensorNode @children  # Picking 1
  description SFString inputOutput
  enabled SFBool inputOutput = TRUE
  intersectionType SFString initializeOnly = "BOUNDS"
  isActive SFBool outputOnly
  matchCriterion SFString inputOutput = "MATCH_ANY"
  metadata SFNode inputOutput <X3DMetadataObject>
  objectType MFString inputOutput = "ALL"
  pickedGeometry MFNode outputOnly <X3DChildNode>
  pickedNormal MFVec3f outputOnly
  pickedPoint MFVec3f outputOnly
  pickedTextureCoordinate MFVec3f outputOnly
  pickingGeometry SFNode inputOutput <X3DGeometryNode>
  pickTarget MFNode inputOutput <X3DGroupingNode|X3DShapeNode|Inline>
  sortOrder SFString initializeOnly = "CLOSEST"
node LineProperties : X3DAppearanceChildNode @lineProperties  # Shape 2
  applied SFBool inputOutput = TRUE
  linetype SFInt32 inputOutput = 1
  linewidthScaleFactor SFFloat inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
node LineSet : X3DGeometryNode @geometry  # Rendering 1
  attrib MFNode inputOutput <X3DVertexAttributeNode>
  color SFNode inputOutput <X3DColorNode>
  coord SFNode inputOutput <X3DCoordinateNode>
  fogCoord SFNode inputOutput <FogCoordinate>
  metadata SFNode inputOutput <X3DMetadataObject>
  normal SFNode inputOutput <X3DNormalNode>
  vertexCount MFInt32 inputOutput
node ListenerPointSource : X3DSoundSourceNode @children  # Sound 2
  description SFString inputOutput
  dopplerEnabled SFBool inputOutput
  elapsedTime SFTime outputOnly
  enabled SFBool inputOutput = TRUE
  gain SFFloat inputOutput = 1
  interauralDistance SFFloat inputOutput
  isActive SFBool outputOnly
  isPaused SFBool outputOnly
  metadata SFNode inputOutput <X3DMetadataObject>
  orientation SFRotation inputOutput = 0 0 1 0
  pauseTime SFTime inputOutput
  position SFVec3f inputOutput
  resumeTime SFTime inputOutput
  startTime SFTime inputOutput
  stopTime SFTime inputOutput
  trackCurrentView SFBool inputOutput
node LoadSensor : X3DNetworkSensorNode @children  # Networking 3
  children MFNode inputOutput <X3DUrlObject>
  description SFString inputOutput
  enabled SFBool inputOutput = TRUE
  isActive SFBool outputOnly
  isLoaded SFBool outputOnly
  loadTime SFTime outputOnly
  metadata SFNode inputOutput <X3DMetadataObject>
  progress SFFloat outputOnly
  timeOut SFTime inputOutput
node LocalFog : X3DChildNode X3DFogObject @children  # EnvironmentalEffects 4
  color SFColor inputOutput = 1 1 1
  enabled SFBool inputOutput = TRUE
  fogType SFString inputOutput = "LINEAR"
  metadata SFNode inputOutput <X3DMetadataObject>
  visibilityRange SFFloat inputOutput
node LOD : X3DGroupingNode @children  # Navigation 2
  addChildren MFNode inputOnly <X3DChildNode>
  bboxCenter SFVec3f initializeOnly
  bboxDisplay SFBool inputOutput
  bboxSize SFVec3f initializeOnly = -1 -1 -1
  center SFVec3f initializeOnly
  children MFNode inputOutput <X3DChildNode>
  forceTransitions SFBool initializeOnly
  level_changed SFInt32 outputOnly
  metadata SFNode inputOutput <X3DMetadataObject>
  range MFFloat initializeOnly
  removeChildren MFNode inputOnly <X3DChildNode>
  visible SFBool inputOutput = TRUE
node Matrix3VertexAttribute : X3DVertexAttributeNode @attrib  # Shaders 1
  metadata SFNode inputOutput <X3DMetadataObject>
  name SFString initializeOnly
  value MFMatrix3f inputOutput
node Matrix4VertexAttribute : X3DVertexAttributeNode @attrib  # Shaders 1
  metadata SFNode inputOutput <X3DMetadataObject>
  name SFString initializeOnly
  value MFMatrix4f inputOutput
node MicrophoneSource : X3DSoundSourceNode @children  # Sound 2
  description SFString inputOutput
  elapsedTime SFTime outputOnly
  enabled SFBool inputOutput = TRUE
  gain SFFloat inputOutput = 1
  isActive SFBool outputOnly
  isPaused SFBool outputOnly
  mediaDeviceID SFString inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  pauseTime SFTime inputOutput
  resumeTime SFTime inputOutput
  startTime SFTime inputOutput
  stopTime SFTime inputOutput
node MovieTexture : X3DSoundSourceNode X3DTexture2DNode X3DUrlObject @texture  # Texturing 3
  autoRefresh SFTime inputOutput
  autoRefreshTimeLimit SFTime inputOutput = 3600
  description SFString inputOutput
  duration_changed SFTime outputOnly
  elapsedTime SFTime outputOnly
  enabled SFBool inputOutput = TRUE
  gain SFFloat inputOutput = 1
  isActive SFBool outputOnly
  isPaused SFBool outputOnly
  load SFBool inputOutput = TRUE
  loop SFBool inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  pauseTime SFTime inputOutput
  pitch SFFloat inputOutput = 1
  repeatS SFBool initializeOnly = TRUE
  repeatT SFBool initializeOnly = TRUE
  resumeTime SFTime inputOutput
  speed SFFloat inputOutput = 1
  startTime SFTime inputOutput
  stopTime SFTime inputOutput
  textureProperties SFNode initializeOnly <TextureProperties>
  url MFString inputOutput
node MultiTexture : X3DTextureNode @texture  # Texturing 2
  alpha SFFloat inputOutput = 1
  color SFColor inputOutput = 1 1 1
  description SFString inputOutput
  function MFString inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  mode MFString inputOutput
  source MFString inputOutput
  texture MFNode inputOutput <X3DSingleTextureNode>
node MultiTextureCoordinate : X3DTextureCoordinateNode @texCoord  # Texturing 2
  metadata SFNode inputOutput <X3DMetadataObject>
  texCoord MFNode inputOutput <X3DSingleTextureCoordinateNode>
node MultiTextureTransform : X3DTextureTransformNode @textureTransform  # Texturing 2
  metadata SFNode inputOutput <X3DMetadataObject>
  textureTransform MFNode inputOutput <X3DSingleTextureTransformNode>
node NormalInterpolator : X3DInterpolatorNode @children  # Interpolation 2
  key MFFloat inputOutput
  keyValue MFVec3f inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  set_fraction SFFloat inputOnly
  value_changed MFVec3f outputOnly
node NurbsCurve : X3DParametricGeometryNode @geometry  # NURBS 1
  closed SFBool initializeOnly
  controlPoint SFNode inputOutput <Coordinate|CoordinateDouble>
  knot MFDouble initializeOnly
  metadata SFNode inputOutput <X3DMetadataObject>
  order SFInt32 initializeOnly = 3
  tessellation SFInt32 inputOutput
  weight MFDouble inputOutput
node NurbsCurve2D : X3DNurbsControlCurveNode @children  # NURBS 3
  closed SFBool initializeOnly
  controlPoint MFVec2d inputOutput
  knot MFDouble initializeOnly
  metadata SFNode inputOutput <X3DMetadataObject>
  order SFInt32 initializeOnly = 3
  tessellation SFInt32 inputOutput
  weight MFDouble inputOutput
node NurbsOrientationInterpolator : X3DChildNode @children  # NURBS 1
  controlPoint SFNode inputOutput <Coordinate|CoordinateDouble>
  knot MFDouble inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  order SFInt32 inputOutput = 3
  set_fraction SFFloat inputOnly
  value_changed SFRotation outputOnly
  weight MFDouble inputOutput
node NurbsPatchSurface : X3DNurbsSurfaceGeometryNode @geometry  # NURBS 1
  controlPoint SFNode inputOutput <Coordinate|CoordinateDouble>
  metadata SFNode inputOutput <X3DMetadataObject>
  solid SFBool initializeOnly = TRUE
  texCoord SFNode inputOutput <X3DSingleTextureCoordinateNode|NurbsTextureCoordinate>
  uClosed SFBool initializeOnly
  uDimension SFInt32 initializeOnly
  uKnot MFDouble initializeOnly
  uOrder SFInt32 initializeOnly = 3
  uTessellation SFInt32 inputOutput
  vClosed SFBool initializeOnly
  vDimension SFInt32 initializeOnly
  vKnot MFDouble initializeOnly
  vOrder SFInt32 initializeOnly = 3
  vTessellation SFInt32 inputOutput
  weight MFDouble inputOutput
node NurbsPositionInterpolator : X3DChildNode @children  # NURBS 1
  controlPoint SFNode inputOutput <Coordinate|CoordinateDouble>
  knot MFDouble inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  order SFInt32 inputOutput = 3
  set_fraction SFFloat inputOnly
  value_changed SFVec3f outputOnly
  weight MFDouble inputOutput
node NurbsSet : X3DChildNode X3DBoundedObject @children  # NURBS 2
  addGeometry MFNode inputOnly <X3DParametricGeometryNode>
  bboxCenter SFVec3f initializeOnly
  bboxDisplay SFBool inputOutput
  bboxSize SFVec3f initializeOnly = -1 -1 -1
  geometry MFNode inputOutput <X3DParametricGeometryNode>
  metadata SFNode inputOutput <X3DMetadataObject>
  removeGeometry MFNode inputOnly <X3DParametricGeometryNode>
  tessellationScale SFFloat inputOutput = 1
  visible SFBool inputOutput = TRUE
node NurbsSurfaceInterpolator : X3DChildNode @children  # NURBS 1
  controlPoint SFNode inputOutput <Coordinate|CoordinateDouble>
  metadata SFNode inputOutput <X3DMetadataObject>
  normal_changed SFVec3f outputOnly
  position_changed SFVec3f outputOnly
  set_fraction SFVec2f inputOnly
  uDimension SFInt32 initializeOnly
  uKnot MFDouble initializeOnly
  uOrder SFInt32 initializeOnly = 3
  vDimension SFInt32 initializeOnly
  vKnot MFDouble initializeOnly
  vOrder SFInt32 initializeOnly = 3
  weight MFDouble inputOutput
node NurbsSweptSurface : X3DParametricGeometryNode @geometry  # NURBS 3
  ccw SFBool initializeOnly = TRUE
  crossSectionCurve SFNode inputOutput <X3DNurbsControlCurveNode>
  metadata SFNode inputOutput <X3DMetadataObject>
  solid SFBool initializeOnly = TRUE
  trajectoryCurve SFNode inputOutput <NurbsCurve>
node NurbsSwungSurface : X3DParametricGeometryNode @geometry  # NURBS 3
  ccw SFBool initializeOnly = TRUE
  metadata SFNode inputOutput <X3DMetadataObject>
  profileCurve SFNode inputOutput <X3DNurbsControlCurveNode>
  solid SFBool initializeOnly = TRUE
  trajectoryCurve SFNode inputOutput <X3DNurbsControlCurveNode>
node NurbsTextureCoordinate : X3DNode @texCoord  # NURBS 1
  controlPoint MFVec2f inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  uDimension SFInt32 initializeOnly
  uKnot MFDouble initializeOnly
  uOrder SFInt32 initializeOnly = 3
  vDimension SFInt32 initializeOnly
  vKnot MFDouble initializeOnly
  vOrder SFInt32 initializeOnly = 3
  weight MFDouble inputOutput
node NurbsTrimmedSurface : X3DNurbsSurfaceGeometryNode @geometry  # NURBS 4
  addTrimmingContour MFNode inputOnly <Contour2D>
  controlPoint SFNode inputOutput <Coordinate|CoordinateDouble>
  metadata SFNode inputOutput <X3DMetadataObject>
  removeTrimmingContour MFNode inputOnly <Contour2D>
  solid SFBool initializeOnly = TRUE
  texCoord SFNode inputOutput <X3DSingleTextureCoordinateNode|NurbsTextureCoordinate>
  trimmingContour MFNode inputOutput <Contour2D>
  uClosed SFBool initializeOnly
  uDimension SFInt32 initializeOnly
  uKnot MFDouble initializeOnly
  uOrder SFInt32 initializeOnly = 3
  uTessellation SFInt32 inputOutput
  vClosed SFBool initializeOnly
  vDimension SFInt32 initializeOnly
  vKnot MFDouble initializeOnly
  vOrder SFInt32 initializeOnly = 3
  vTessellation SFInt32 inputOutput
  weight MFDouble inputOutput
node OpacityMapVolumeStyle : X3DComposableVolumeRenderStyleNode @renderStyle  # VolumeRendering 1
  enabled SFBool inputOutput = TRUE
  metadata SFNode inputOutput <X3DMetadataObject>
  transferFunction SFNode inputOutput <X3DTexture2DNode|X3DTexture3DNode>
node OrientationChaser : X3DChaserNode @children  # Followers 1
  duration SFTime initializeOnly = 1
  initialDestination SFRotation initializeOnly = 0 1 0 0
  initialValue SFRotation initializeOnly = 0 1 0 0
  isActive SFBool outputOnly
  metadata SFNode inputOutput <X3DMetadataObject>
  set_destination SFRotation inputOnly
  set_value SFRotation inputOnly
  value_changed SFRotation outputOnly
node OrientationDamper : X3DDamperNode @children  # Followers 1
  initialDestination SFRotation initializeOnly = 0 1 0 0
  initialValue SFRotation initializeOnly = 0 1 0 0
  isActive SFBool outputOnly
  metadata SFNode inputOutput <X3DMetadataObject>
  order SFInt32 initializeOnly = 3
  set_destination SFRotation inputOnly
  set_value SFRotation inputOnly
  tau SFTime inputOutput = 0.3
  tolerance SFFloat inputOutput = -1
  value_changed SFRotation outputOnly
node OrthoViewpoint : X3DViewpointNode @children  # Navigation 3
  bindTime SFTime outputOnly
  centerOfRotation SFVec3f inputOutput
  description SFString inputOutput
  farDistance SFFloat inputOutput = -1
  fieldOfView MFFloat inputOutput = -1 -1 1 1
  isBound SFBool outputOnly
  jump SFBool inputOutput = TRUE
  metadata SFNode inputOutput <X3DMetadataObject>
  navigationInfo SFNode inputOutput <NavigationInfo>
  nearDistance SFFloat inputOutput = -1
  orientation SFRotation inputOutput = 0 0 1 0
  position SFVec3f inputOutput = 0 0 10
  retainUserOffsets SFBool inputOutput
  set_bind SFBool inputOnly
  viewAll SFBool inputOutput
node OscillatorSource : X3DSoundSourceNode @children  # Sound 2
  description SFString inputOutput
  detune SFFloat inputOutput
  elapsedTime SFTime outputOnly
  enabled SFBool inputOutput = TRUE
  frequency SFFloat inputOutput = 440
  gain SFFloat inputOutput = 1
  isActive SFBool outputOnly
  isPaused SFBool outputOnly
  metadata SFNode inputOutput <X3DMetadataObject>
  pauseTime SFTime inputOutput
  resumeTime SFTime inputOutput
  startTime SFTime inputOutput
  stopTime SFTime inputOutput
node PackagedShader : X3DShaderNode X3DUrlObject X3DProgrammableShaderObject @shaders  # Shaders 1
  activate SFBool inputOnly
  autoRefresh SFTime inputOutput
  autoRefreshTimeLimit SFTime inputOutput = 3600
  description SFString inputOutput
  isSelected SFBool outputOnly
  isValid SFBool outputOnly
  language SFString initializeOnly
  load SFBool inputOutput = TRUE
  metadata SFNode inputOutput <X3DMetadataObject>
  url MFString inputOutput
node ParticleSystem : X3DShapeNode @children  # ParticleSystems 2
  appearance SFNode inputOutput <X3DAppearanceNode>
  bboxCenter SFVec3f initializeOnly
  bboxDisplay SFBool inputOutput
  bboxSize SFVec3f initializeOnly = -1 -1 -1
  castShadow SFBool inputOutput = TRUE
  color SFNode initializeOnly <X3DColorNode>
  colorKey MFFloat initializeOnly
  createParticles SFBool inputOutput = TRUE
  emitter SFNode initializeOnly <X3DParticleEmitterNode>
  enabled SFBool inputOutput = TRUE
  geometry SFNode inputOutput <X3DGeometryNode>
  geometryType SFString initializeOnly = "QUAD"
  isActive SFBool outputOnly
  lifetimeVariation SFFloat inputOutput = 0.25
  maxParticles SFInt32 inputOutput = 200
  metadata SFNode inputOutput <X3DMetadataObject>
  particleLifetime SFFloat inputOutput = 5
  particleSize SFVec2f inputOutput = 0.02 0.02
  physics MFNode initializeOnly <X3DParticlePhysicsModelNode>
  texCoord SFNode initializeOnly <TextureCoordinate|TextureCoordinateGenerator>
  texCoordKey MFFloat initializeOnly
  visible SFBool inputOutput = TRUE
node PeriodicWave : X3DSoundNode @periodicWave  # Sound 2
  description SFString inputOutput
  enabled SFBool inputOutput = TRUE
  metadata SFNode inputOutput <X3DMetadataObject>
  optionsImag MFFloat inputOutput
  optionsReal MFFloat inputOutput
  type SFString inputOutput = "SQUARE"
node PhysicalMaterial : X3DOneSidedMaterialNode @material  # Shape 2
  baseColor SFColor inputOutput = 1 1 1
  baseTexture SFNode inputOutput <X3DSingleTextureNode>
  baseTextureMapping SFString inputOutput
  emissiveColor SFColor inputOutput
  emissiveTexture SFNode inputOutput <X3DSingleTextureNode>
  emissiveTextureMapping SFString inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  metallic SFFloat inputOutput = 1
  metallicRoughnessTexture SFNode inputOutput <X3DSingleTextureNode>
  metallicRoughnessTextureMapping SFString inputOutput
  normalScale SFFloat inputOutput = 1
  normalTexture SFNode inputOutput <X3DSingleTextureNode>
  normalTextureMapping SFString inputOutput
  occlusionStrength SFFloat inputOutput = 1
  occlusionTexture SFNode inputOutput <X3DSingleTextureNode>
  occlusionTextureMapping SFString inputOutput
  roughness SFFloat inputOutput = 1
  transparency SFFloat inputOutput
node PickableGroup : X3DGroupingNode X3DPickableObject @children  # Picking 1
  addChildren MFNode inputOnly <X3DChildNode>
  bboxCenter SFVec3f initializeOnly
  bboxDisplay SFBool inputOutput
  bboxSize SFVec3f initializeOnly = -1 -1 -1
  children MFNode inputOutput <X3DChildNode>
  description SFString inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  objectType MFString inputOutput = "ALL"
  pickable SFBool inputOutput = TRUE
  removeChildren MFNode inputOnly <X3DChildNode>
  visible SFBool inputOutput = TRUE
node PixelTexture : X3DTexture2DNode @texture  # Texturing 1
  description SFString inputOutput
  image SFImage inputOutput = 0 0 0
  metadata SFNode inputOutput <X3DMetadataObject>
  repeatS SFBool initializeOnly = TRUE
  repeatT SFBool initializeOnly = TRUE
  textureProperties SFNode initializeOnly <TextureProperties>
node PixelTexture3D : X3DTexture3DNode @texture  # Texturing3D 1
  description SFString inputOutput
  image MFInt32 inputOutput = 0 0 0 0
  metadata SFNode inputOutput <X3DMetadataObject>
  repeatR SFBool initializeOnly
  repeatS SFBool initializeOnly
  repeatT SFBool initializeOnly
  textureProperties SFNode initializeOnly <TextureProperties>
node PlaneSensor : X3DDragSensorNode @children  # PointingDeviceSensor 1
  autoOffset SFBool inputOutput = TRUE
  axisRotation SFRotation inputOutput = 0 0 1 0
  description SFString inputOutput
  enabled SFBool inputOutput = TRUE
  isActive SFBool outputOnly
  isOver SFBool outputOnly
  maxPosition SFVec2f inputOutput = -1 -1
  metadata SFNode inputOutput <X3DMetadataObject>
  minPosition SFVec2f inputOutput
  offset SFVec3f inputOutput
  trackPoint_changed SFVec3f outputOnly
  translation_changed SFVec3f outputOnly
node PointEmitter : X3DParticleEmitterNode @emitter  # ParticleSystems 1
  direction SFVec3f inputOutput = 0 1 0
  mass SFFloat inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  on SFBool inputOutput = TRUE
  position SFVec3f inputOutput
  speed SFFloat inputOutput
  surfaceArea SFFloat inputOutput
  variation SFFloat inputOutput = 0.25
node PointLight : X3DLightNode @children  # Lighting 2
  ambientIntensity SFFloat inputOutput
  attenuation SFVec3f inputOutput = 1 0 0
  color SFColor inputOutput = 1 1 1
  global SFBool inputOutput = TRUE
  intensity SFFloat inputOutput = 1
  location SFVec3f inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  on SFBool inputOutput = TRUE
  radius SFFloat inputOutput = 100
  shadowIntensity SFFloat inputOutput = 1
  shadows SFBool inputOutput
node PointPickSensor : X3DPickSensorNode @children  # Picking 1
  description SFString inputOutput
  enabled SFBool inputOutput = TRUE
  intersectionType SFString initializeOnly = "BOUNDS"
  isActive SFBool outputOnly
  matchCriterion SFString inputOutput = "MATCH_ANY"
  metadata SFNode inputOutput <X3DMetadataObject>
  objectType MFString inputOutput = "ALL"
  pickedGeometry MFNode outputOnly <X3DChildNode>
  pickedPoint MFVec3f outputOnly
  pickingGeometry SFNode inputOutput <X3DGeometryNode>
  pickTarget MFNode inputOutput <X3DGroupingNode|X3DShapeNode|Inline>
  sortOrder SFString initializeOnly = "CLOSEST"
node PointProperties : X3DAppearanceChildNode @pointProperties  # Shape 5
  attenuation SFVec3f inputOutput = 1 0 0
  metadata SFNode inputOutput <X3DMetadataObject>
  pointSizeMaxValue SFFloat inputOutput = 1
  pointSizeMinValue SFFloat inputOutput = 1
  pointSizeScaleFactor SFFloat inputOutput = 1
node PointSet : X3DGeometryNode @geometry  # Rendering 1
  attrib MFNode inputOutput <X3DVertexAttributeNode>
  color SFNode inputOutput <X3DColorNode>
  coord SFNode inputOutput <X3DCoordinateNode>
  fogCoord SFNode inputOutput <FogCoordinate>
  metadata SFNode inputOutput <X3DMetadataObject>
  normal SFNode inputOutput <X3DNormalNode>
node Polyline2D : X3DGeometryNode @geometry  # Geometry2D 1
  lineSegments MFVec2f initializeOnly
  metadata SFNode inputOutput <X3DMetadataObject>
node PolylineEmitter : X3DParticleEmitterNode @emitter  # ParticleSystems 1
  coord SFNode inputOutput <X3DCoordinateNode>
  coordIndex MFInt32 initializeOnly = -1
  direction SFVec3f inputOutput = 0 1 0
  mass SFFloat inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  on SFBool inputOutput = TRUE
  set_coordIndex MFInt32 inputOnly
  speed SFFloat inputOutput
  surfaceArea SFFloat inputOutput
  variation SFFloat inputOutput = 0.25
node Polypoint2D : X3DGeometryNode @geometry  # Geometry2D 1
  metadata SFNode inputOutput <X3DMetadataObject>
  point MFVec2f inputOutput
node PositionChaser : X3DChaserNode @children  # Followers 1
  duration SFTime initializeOnly = 1
  initialDestination SFVec3f initializeOnly
  initialValue SFVec3f initializeOnly
  isActive SFBool outputOnly
  metadata SFNode inputOutput <X3DMetadataObject>
  set_destination SFVec3f inputOnly
  set_value SFVec3f inputOnly
  value_changed SFVec3f outputOnly
node PositionChaser2D : X3DChaserNode @children  # Followers 1
  duration SFTime initializeOnly = 1
  initialDestination SFVec2f initializeOnly
  initialValue SFVec2f initializeOnly
  isActive SFBool outputOnly
  metadata SFNode inputOutput <X3DMetadataObject>
  set_destination SFVec2f inputOnly
  set_value SFVec2f inputOnly
  value_changed SFVec2f outputOnly
node PositionDamper : X3DDamperNode @children  # Followers 1
  initialDestination SFVec3f initializeOnly
  initialValue SFVec3f initializeOnly
  isActive SFBool outputOnly
  metadata SFNode inputOutput <X3DMetadataObject>
  order SFInt32 initializeOnly = 3
  set_destination SFVec3f inputOnly
  set_value SFVec3f inputOnly
  tau SFTime inputOutput = 0.3
  tolerance SFFloat inputOutput = -1
  value_changed SFVec3f outputOnly
node PositionDamper2D : X3DDamperNode @children  # Followers 1
  initialDestination SFVec2f initializeOnly
  initialValue SFVec2f initializeOnly
  isActive SFBool outputOnly
  metadata SFNode inputOutput <X3DMetadataObject>
  order SFInt32 initializeOnly = 3
  set_destination SFVec2f inputOnly
  set_value SFVec2f inputOnly
  tau SFTime inputOutput = 0.3
  tolerance SFFloat inputOutput = -1
  value_changed SFVec2f outputOnly
node PositionInterpolator2D : X3DInterpolatorNode @children  # Interpolation 3
  key MFFloat inputOutput
  keyValue MFVec2f inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  set_fraction SFFloat inputOnly
  value_changed SFVec2f outputOnly
node PrimitivePickSensor : X3DPickSensorNode @children  # Picking 2
  description SFString inputOutput
  enabled SFBool inputOutput = TRUE
  intersectionType SFString initializeOnly = "BOUNDS"
  isActive SFBool outputOnly
  matchCriterion SFString inputOutput = "MATCH_ANY"
  metadata SFNode inputOutput <X3DMetadataObject>
  objectType MFString inputOutput = "ALL"
  pickedGeometry MFNode outputOnly <X3DChildNode>
  pickingGeometry SFNode inputOutput <X3DGeometryNode>
  pickTarget MFNode inputOutput <X3DGroupingNode|X3DShapeNode|Inline>
  sortOrder SFString initializeOnly = "CLOSEST"
node ProgramShader : X3DShaderNode @shaders  # Shaders 1
  activate SFBool inputOnly
  isSelected SFBool outputOnly
  isValid SFBool outputOnly
  language SFString initializeOnly
  metadata SFNode inputOutput <X3DMetadataObject>
  programs MFNode inputOutput <ShaderProgram>
node ProjectionVolumeStyle : X3DVolumeRenderStyleNode @renderStyle  # VolumeRendering 2
  enabled SFBool inputOutput = TRUE
  intensityThreshold SFFloat inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  type SFString inputOutput = "MAX"
node ProximitySensor : X3DEnvironmentalSensorNode @children  # EnvironmentalSensor 1
  center SFVec3f inputOutput
  centerOfRotation_changed SFVec3f outputOnly
  description SFString inputOutput
  enabled SFBool inputOutput = TRUE
  enterTime SFTime outputOnly
  exitTime SFTime outputOnly
  isActive SFBool outputOnly
  metadata SFNode inputOutput <X3DMetadataObject>
  orientation_changed SFRotation outputOnly
  position_changed SFVec3f outputOnly
  size SFVec3f inputOutput
node QuadSet : X3DComposedGeometryNode @geometry  # CADGeometry 1
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
node ReceiverPdu : X3DNetworkSensorNode X3DBoundedObject @children  # DIS 1
  address SFString inputOutput = "localhost"
  applicationID SFInt32 inputOutput
  bboxCenter SFVec3f initializeOnly
  bboxDisplay SFBool inputOutput
  bboxSize SFVec3f initializeOnly = -1 -1 -1
  description SFString inputOutput
  enabled SFBool inputOutput = TRUE
  entityID SFInt32 inputOutput
  geoCoords SFVec3d inputOutput
  geoSystem MFString initializeOnly = "GD" "WE"
  isActive SFBool outputOnly
  isNetworkReader SFBool outputOnly
  isNetworkWriter SFBool outputOnly
  isRtpHeaderHeard SFBool outputOnly
  isStandAlone SFBool outputOnly
  metadata SFNode inputOutput <X3DMetadataObject>
  multicastRelayHost SFString inputOutput
  multicastRelayPort SFInt32 inputOutput
  networkMode SFString inputOutput = "standAlone"
  port SFInt32 inputOutput
  radioID SFInt32 inputOutput
  readInterval SFTime inputOutput = 0.1
  receivedPower SFFloat inputOutput
  receiverState SFInt32 inputOutput
  rtpHeaderExpected SFBool inputOutput
  siteID SFInt32 inputOutput
  timestamp SFTime outputOnly
  transmitterApplicationID SFInt32 inputOutput
  transmitterEntityID SFInt32 inputOutput
  transmitterRadioID SFInt32 inputOutput
  transmitterSiteID SFInt32 inputOutput
  visible SFBool inputOutput = TRUE
  whichGeometry SFInt32 inputOutput = 1
  writeInterval SFTime inputOutput = 1
node Rectangle2D : X3DGeometryNode @geometry  # Geometry2D 1
  metadata SFNode inputOutput <X3DMetadataObject>
  size SFVec2f initializeOnly = 2 2
  solid SFBool initializeOnly
node ScalarChaser : X3DChaserNode @children  # Followers 1
  duration SFTime initializeOnly = 1
  initialDestination SFFloat initializeOnly
  initialValue SFFloat initializeOnly
  isActive SFBool outputOnly
  metadata SFNode inputOutput <X3DMetadataObject>
  set_destination SFFloat inputOnly
  set_value SFFloat inputOnly
  value_changed SFFloat outputOnly
node ScalarDamper : X3DDamperNode @children  # Followers 1
  initialDestination SFFloat initializeOnly
  initialValue SFFloat initializeOnly
  isActive SFBool outputOnly
  metadata SFNode inputOutput <X3DMetadataObject>
  order SFInt32 initializeOnly = 3
  set_destination SFFloat inputOnly
  set_value SFFloat inputOnly
  tau SFTime inputOutput = 0.3
  tolerance SFFloat inputOutput = -1
  value_changed SFFloat outputOnly
node ScalarInterpolator : X3DInterpolatorNode @children  # Interpolation 1
  key MFFloat inputOutput
  keyValue MFFloat inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  set_fraction SFFloat inputOnly
  value_changed SFFloat outputOnly
node ScreenFontStyle : X3DFontStyleNode @fontStyle  # Layout 2
  family MFString inputOutput = "SERIF"
  horizontal SFBool inputOutput = TRUE
  justify MFString inputOutput = "BEGIN"
  language SFString inputOutput
  leftToRight SFBool inputOutput = TRUE
  metadata SFNode inputOutput <X3DMetadataObject>
  pointSize SFFloat inputOutput = 12
  spacing SFFloat inputOutput = 1
  topToBottom SFBool inputOutput = TRUE
node ScreenGroup : X3DGroupingNode @children  # Layout 2
  addChildren MFNode inputOnly <X3DChildNode>
  bboxCenter SFVec3f initializeOnly
  bboxDisplay SFBool inputOutput
  bboxSize SFVec3f initializeOnly = -1 -1 -1
  children MFNode inputOutput <X3DChildNode>
  metadata SFNode inputOutput <X3DMetadataObject>
  removeChildren MFNode inputOnly <X3DChildNode>
  visible SFBool inputOutput = TRUE
node SegmentedVolumeData : X3DVolumeDataNode @children  # VolumeRendering 2
  bboxCenter SFVec3f initializeOnly
  bboxDisplay SFBool inputOutput
  bboxSize SFVec3f initializeOnly = -1 -1 -1
  dimensions SFVec3f inputOutput = 1 1 1
  metadata SFNode inputOutput <X3DMetadataObject>
  renderStyle MFNode inputOutput <X3DVolumeRenderStyleNode>
  segmentEnabled MFBool inputOutput
  segmentIdentifiers SFNode inputOutput <X3DTexture3DNode>
  visible SFBool inputOutput = TRUE
  voxels SFNode inputOutput <X3DTexture3DNode>
node ShadedVolumeStyle : X3DComposableVolumeRenderStyleNode @renderStyle  # VolumeRendering 3
  enabled SFBool inputOutput = TRUE
  lighting SFBool inputOutput
  material SFNode inputOutput <X3DMaterialNode>
  metadata SFNode inputOutput <X3DMetadataObject>
  phaseFunction SFString initializeOnly = "Henyey-Greenstein"
  shadows SFBool inputOutput
  surfaceNormals SFNode inputOutput <X3DTexture3DNode>
node ShaderPart : X3DNode X3DUrlObject @parts  # Shaders 1
  autoRefresh SFTime inputOutput
  autoRefreshTimeLimit SFTime inputOutput = 3600
  description SFString inputOutput
  load SFBool inputOutput = TRUE
  metadata SFNode inputOutput <X3DMetadataObject>
  sourceCode SFString inputOutput
  type SFString initializeOnly = "VERTEX"
  url MFString inputOutput
node ShaderProgram : X3DNode X3DUrlObject X3DProgrammableShaderObject @programs  # Shaders 1
  autoRefresh SFTime inputOutput
  autoRefreshTimeLimit SFTime inputOutput = 3600
  description SFString inputOutput
  load SFBool inputOutput = TRUE
  metadata SFNode inputOutput <X3DMetadataObject>
  sourceCode SFString inputOutput
  type SFString initializeOnly = "VERTEX"
  url MFString inputOutput
node SignalPdu : X3DNetworkSensorNode X3DBoundedObject @children  # DIS 1
  address SFString inputOutput = "localhost"
  applicationID SFInt32 inputOutput
  bboxCenter SFVec3f initializeOnly
  bboxDisplay SFBool inputOutput
  bboxSize SFVec3f initializeOnly = -1 -1 -1
  data MFInt32 inputOutput
  dataLength SFInt32 inputOutput
  description SFString inputOutput
  enabled SFBool inputOutput = TRUE
  encodingScheme SFInt32 inputOutput
  entityID SFInt32 inputOutput
  geoCoords SFVec3d inputOutput
  geoSystem MFString initializeOnly = "GD" "WE"
  isActive SFBool outputOnly
  isNetworkReader SFBool outputOnly
  isNetworkWriter SFBool outputOnly
  isRtpHeaderHeard SFBool outputOnly
  isStandAlone SFBool outputOnly
  metadata SFNode inputOutput <X3DMetadataObject>
  multicastRelayHost SFString inputOutput
  multicastRelayPort SFInt32 inputOutput
  networkMode SFString inputOutput = "standAlone"
  port SFInt32 inputOutput
  radioID SFInt32 inputOutput
  readInterval SFTime inputOutput = 0.1
  rtpHeaderExpected SFBool inputOutput
  sampleRate SFInt32 inputOutput
  samples SFInt32 inputOutput
  siteID SFInt32 inputOutput
  tdlType SFInt32 inputOutput
  timestamp SFTime outputOnly
  visible SFBool inputOutput = TRUE
  whichGeometry SFInt32 inputOutput = 1
  writeInterval SFTime inputOutput = 1
node SilhouetteEnhancementVolumeStyle : X3DComposableVolumeRenderStyleNode @renderStyle  # VolumeRendering 2
  enabled SFBool inputOutput = TRUE
  metadata SFNode inputOutput <X3DMetadataObject>
  silhouetteBoundaryOpacity SFFloat inputOutput
  silhouetteRetainedOpacity SFFloat inputOutput = 1
  silhouetteSharpness SFFloat inputOutput = 0.5
  surfaceNormals SFNode inputOutput <X3DTexture3DNode>
node Sound : X3DSoundNode @children  # Sound 1
  description SFString inputOutput
  direction SFVec3f inputOutput = 0 0 1
  enabled SFBool inputOutput = TRUE
  intensity SFFloat inputOutput = 1
  location SFVec3f inputOutput
  maxBack SFFloat inputOutput = 10
  maxFront SFFloat inputOutput = 10
  metadata SFNode inputOutput <X3DMetadataObject>
  minBack SFFloat inputOutput = 1
  minFront SFFloat inputOutput = 1
  priority SFFloat inputOutput
  source SFNode inputOutput <X3DSoundSourceNode>
  spatialize SFBool initializeOnly = TRUE
node SpatialSound : X3DSoundNode @children  # Sound 2
  children MFNode inputOutput <Analyser|AudioClip|AudioDestination|BiquadFilter|BufferAudioSource|ChannelMerger|ChannelSelector|ChannelSplitter|Convolver|Delay|DynamicsCompressor|Gain|ListenerPointSource|MicrophoneSource|MovieTexture|OscillatorSource|Sound|SpatialSound|StreamAudioDestination|StreamAudioSource|WaveShaper>
  coneInnerAngle SFFloat inputOutput = 6.2832
  coneOuterAngle SFFloat inputOutput = 6.2832
  coneOuterGain SFFloat inputOutput
  description SFString inputOutput
  direction SFVec3f inputOutput = 0 0 1
  distanceModel SFString inputOutput = "INVERSE"
  dopplerEnabled SFBool inputOutput
  enabled SFBool inputOutput = TRUE
  enableHRTF SFBool inputOutput
  gain SFFloat inputOutput = 1
  intensity SFFloat inputOutput = 1
  location SFVec3f inputOutput
  maxDistance SFFloat inputOutput = 10000
  metadata SFNode inputOutput <X3DMetadataObject>
  priority SFFloat inputOutput
  referenceDistance SFFloat inputOutput = 1
  rolloffFactor SFFloat inputOutput = 1
  spatialize SFBool initializeOnly = TRUE
node SphereSensor : X3DDragSensorNode @children  # PointingDeviceSensor 1
  autoOffset SFBool inputOutput = TRUE
  description SFString inputOutput
  enabled SFBool inputOutput = TRUE
  isActive SFBool outputOnly
  isOver SFBool outputOnly
  metadata SFNode inputOutput <X3DMetadataObject>
  offset SFRotation inputOutput = 0 1 0 0
  rotation_changed SFRotation outputOnly
  trackPoint_changed SFVec3f outputOnly
node SplinePositionInterpolator : X3DInterpolatorNode @children  # Interpolation 4
  closed SFBool inputOutput
  key MFFloat inputOutput
  keyValue MFVec3f inputOutput
  keyVelocity MFVec3f inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  normalizeVelocity SFBool inputOutput
  set_fraction SFFloat inputOnly
  value_changed SFVec3f outputOnly
node SplinePositionInterpolator2D : X3DInterpolatorNode @children  # Interpolation 4
  closed SFBool inputOutput
  key MFFloat inputOutput
  keyValue MFVec2f inputOutput
  keyVelocity MFVec2f inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  normalizeVelocity SFBool inputOutput
  set_fraction SFFloat inputOnly
  value_changed SFVec2f outputOnly
node SplineScalarInterpolator : X3DInterpolatorNode @children  # Interpolation 4
  closed SFBool inputOutput
  key MFFloat inputOutput
  keyValue MFFloat inputOutput
  keyVelocity MFFloat inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  normalizeVelocity SFBool inputOutput
  set_fraction SFFloat inputOnly
  value_changed SFFloat outputOnly
node SpotLight : X3DLightNode @children  # Lighting 2
  ambientIntensity SFFloat inputOutput
  attenuation SFVec3f inputOutput = 1 0 0
  beamWidth SFFloat inputOutput = 0.589049
  color SFColor inputOutput = 1 1 1
  cutOffAngle SFFloat inputOutput = 1.570796
  direction SFVec3f inputOutput = 0 0 -1
  global SFBool inputOutput = TRUE
  intensity SFFloat inputOutput = 1
  location SFVec3f inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  on SFBool inputOutput = TRUE
  radius SFFloat inputOutput = 100
  shadowIntensity SFFloat inputOutput = 1
  shadows SFBool inputOutput
node SquadOrientationInterpolator : X3DInterpolatorNode @children  # Interpolation 5
  key MFFloat inputOutput
  keyValue MFRotation inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  normalizeVelocity SFBool inputOutput
  set_fraction SFFloat inputOnly
  value_changed SFRotation outputOnly
node StaticGroup : X3DChildNode X3DBoundedObject @children  # Grouping 3
  bboxCenter SFVec3f initializeOnly
  bboxDisplay SFBool inputOutput
  bboxSize SFVec3f initializeOnly = -1 -1 -1
  children MFNode initializeOnly <X3DChildNode>
  metadata SFNode inputOutput <X3DMetadataObject>
  visible SFBool inputOutput = TRUE
node StreamAudioDestination : X3DSoundDestinationNode @children  # Sound 2
  channelCount SFInt32 outputOnly
  channelCountMode SFString inputOutput = "MAX"
  channelInterpretation SFString inputOutput = "SPEAKERS"
  children MFNode inputOutput <Analyser|AudioClip|AudioDestination|BiquadFilter|BufferAudioSource|ChannelMerger|ChannelSelector|ChannelSplitter|Convolver|Delay|DynamicsCompressor|Gain|ListenerPointSource|MicrophoneSource|MovieTexture|OscillatorSource|Sound|SpatialSound|StreamAudioDestination|StreamAudioSource|WaveShaper>
  description SFString inputOutput
  enabled SFBool inputOutput = TRUE
  gain SFFloat inputOutput = 1
  isActive SFBool outputOnly
  mediaDeviceID SFString inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  streamIdentifier SFString inputOutput
node StreamAudioSource : X3DSoundSourceNode @children  # Sound 2
  channelCountMode SFString inputOutput = "MAX"
  channelInterpretation SFString inputOutput = "SPEAKERS"
  description SFString inputOutput
  elapsedTime SFTime outputOnly
  enabled SFBool inputOutput = TRUE
  gain SFFloat inputOutput = 1
  isActive SFBool outputOnly
  isPaused SFBool outputOnly
  metadata SFNode inputOutput <X3DMetadataObject>
  pauseTime SFTime inputOutput
  resumeTime SFTime inputOutput
  startTime SFTime inputOutput
  stopTime SFTime inputOutput
  streamIdentifier SFString inputOutput
node StringSensor : X3DKeyDeviceSensorNode @children  # KeyDeviceSensor 2
  deletionAllowed SFBool inputOutput = TRUE
  description SFString inputOutput
  enabled SFBool inputOutput = TRUE
  enteredText SFString outputOnly
  finalText SFString outputOnly
  isActive SFBool outputOnly
  metadata SFNode inputOutput <X3DMetadataObject>
node SurfaceEmitter : X3DParticleEmitterNode @emitter  # ParticleSystems 2
  mass SFFloat inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  on SFBool inputOutput = TRUE
  speed SFFloat inputOutput
  surface SFNode initializeOnly <X3DGeometryNode>
  surfaceArea SFFloat inputOutput
  variation SFFloat inputOutput = 0.25
node Switch : X3DGroupingNode @children  # Grouping 2
  addChildren MFNode inputOnly <X3DChildNode>
  bboxCenter SFVec3f initializeOnly
  bboxDisplay SFBool inputOutput
  bboxSize SFVec3f initializeOnly = -1 -1 -1
  children MFNode inputOutput <X3DChildNode>
  metadata SFNode inputOutput <X3DMetadataObject>
  removeChildren MFNode inputOnly <X3DChildNode>
  visible SFBool inputOutput = TRUE
  whichChoice SFInt32 inputOutput = -1
node TexCoordChaser2D : X3DChaserNode @children  # Followers 1
  duration SFTime initializeOnly = 1
  initialDestination MFVec2f initializeOnly
  initialValue MFVec2f initializeOnly
  isActive SFBool outputOnly
  metadata SFNode inputOutput <X3DMetadataObject>
  set_destination MFVec2f inputOnly
  set_value MFVec2f inputOnly
  value_changed MFVec2f outputOnly
node TexCoordDamper2D : X3DDamperNode @children  # Followers 1
  initialDestination MFVec2f initializeOnly
  initialValue MFVec2f initializeOnly
  isActive SFBool outputOnly
  metadata SFNode inputOutput <X3DMetadataObject>
  order SFInt32 initializeOnly = 3
  set_destination MFVec2f inputOnly
  set_value MFVec2f inputOnly
  tau SFTime inputOutput = 0.3
  tolerance SFFloat inputOutput = -1
  value_changed MFVec2f outputOnly
node Text : X3DGeometryNode @geometry  # Text 1
  fontStyle SFNode inputOutput <X3DFontStyleNode>
  length MFFloat inputOutput
  lineBounds MFVec2f outputOnly
  maxExtent SFFloat inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  origin SFVec3f outputOnly
  solid SFBool initializeOnly
  string MFString inputOutput
  textBounds SFVec2f outputOnly
node TextureBackground : X3DBackgroundNode @children  # EnvironmentalEffects 3
  backTexture SFNode inputOutput <X3DTexture2DNode|MultiTexture>
  bindTime SFTime outputOnly
  bottomTexture SFNode inputOutput <X3DTexture2DNode|MultiTexture>
  frontTexture SFNode inputOutput <X3DTexture2DNode|MultiTexture>
  groundAngle MFFloat inputOutput
  groundColor MFColor inputOutput
  isBound SFBool outputOnly
  leftTexture SFNode inputOutput <X3DTexture2DNode|MultiTexture>
  metadata SFNode inputOutput <X3DMetadataObject>
  rightTexture SFNode inputOutput <X3DTexture2DNode|MultiTexture>
  set_bind SFBool inputOnly
  skyAngle MFFloat inputOutput
  skyColor MFColor inputOutput = 0 0 0
  topTexture SFNode inputOutput <X3DTexture2DNode|MultiTexture>
  transparency SFFloat inputOutput
node TextureCoordinate3D : X3DSingleTextureCoordinateNode @texCoord  # Texturing3D 1
  mapping SFString inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  point MFVec3f inputOutput
node TextureCoordinate4D : X3DSingleTextureCoordinateNode @texCoord  # Texturing3D 1
  mapping SFString inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  point MFVec4f inputOutput
node TextureCoordinateGenerator : X3DSingleTextureCoordinateNode @texCoord  # Texturing 2
  mapping SFString inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  mode SFString inputOutput = "SPHERE"
  parameter MFFloat inputOutput
node TextureProjector : X3DTextureProjectorNode @children  # TextureProjection 2
  ambientIntensity SFFloat inputOutput
  aspectRatio SFFloat outputOnly
  color SFColor inputOutput = 1 1 1
  description SFString inputOutput
  direction SFVec3f inputOutput = 0 0 1
  farDistance SFFloat inputOutput = -1
  fieldOfView SFFloat inputOutput = 0.7854
  global SFBool inputOutput = TRUE
  intensity SFFloat inputOutput = 1
  location SFVec3f inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  nearDistance SFFloat inputOutput = -1
  on SFBool inputOutput = TRUE
  shadowIntensity SFFloat inputOutput = 1
  shadows SFBool inputOutput
  texture SFNode inputOutput <X3DTexture2DNode>
  upVector SFVec3f inputOutput = 0 1 0
node TextureProjectorParallel : X3DTextureProjectorNode @children  # TextureProjection 2
  ambientIntensity SFFloat inputOutput
  aspectRatio SFFloat outputOnly
  color SFColor inputOutput = 1 1 1
  description SFString inputOutput
  direction SFVec3f inputOutput = 0 0 1
  farDistance SFFloat inputOutput = -1
  fieldOfView SFVec4f inputOutput = -1 -1 1 1
  global SFBool inputOutput = TRUE
  intensity SFFloat inputOutput = 1
  location SFVec3f inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  nearDistance SFFloat inputOutput = -1
  on SFBool inputOutput = TRUE
  shadowIntensity SFFloat inputOutput = 1
  shadows SFBool inputOutput
  texture SFNode inputOutput <X3DTexture2DNode>
  upVector SFVec3f inputOutput = 0 1 0
node TextureProperties : X3DNode @textureProperties  # Texturing 2
  anisotropicDegree SFFloat inputOutput = 1
  borderColor SFColorRGBA inputOutput
  borderWidth SFInt32 inputOutput
  boundaryModeR SFString inputOutput = "REPEAT"
  boundaryModeS SFString inputOutput = "REPEAT"
  boundaryModeT SFString inputOutput = "REPEAT"
  generateMipMaps SFBool initializeOnly
  magnificationFilter SFString inputOutput = "FASTEST"
  metadata SFNode inputOutput <X3DMetadataObject>
  minificationFilter SFString inputOutput = "FASTEST"
  textureCompression SFString inputOutput = "FASTEST"
  texturePriority SFFloat inputOutput
node TextureTransform : X3DTextureTransformNode @textureTransform  # Texturing 1
  center SFVec2f inputOutput
  mapping SFString inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  rotation SFFloat inputOutput
  scale SFVec2f inputOutput = 1 1
  translation SFVec2f inputOutput
node TextureTransform3D : X3DTextureTransformNode @textureTransform  # Texturing3D 1
  center SFVec3f inputOutput
  mapping SFString inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  rotation SFRotation inputOutput = 0 0 1 0
  scale SFVec3f inputOutput = 1 1 1
  translation SFVec3f inputOutput
node TextureTransformMatrix3D : X3DTextureTransformNode @textureTransform  # Texturing3D 1
  mapping SFString inputOutput
  matrix SFMatrix4f inputOutput = 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1
  metadata SFNode inputOutput <X3DMetadataObject>
node TimeTrigger : X3DTriggerNode @children  # EventUtilities 1
  metadata SFNode inputOutput <X3DMetadataObject>
  set_boolean SFBool inputOnly
  triggerTime SFTime outputOnly
node ToneMappedVolumeStyle : X3DComposableVolumeRenderStyleNode @renderStyle  # VolumeRendering 2
  coolColor SFColorRGBA inputOutput = 0 0 1 0
  enabled SFBool inputOutput = TRUE
  metadata SFNode inputOutput <X3DMetadataObject>
  surfaceNormals SFNode inputOutput <X3DTexture3DNode>
  warmColor SFColorRGBA inputOutput = 1 1 0 0
node TouchSensor : X3DTouchSensorNode @children  # PointingDeviceSensor 1
  description SFString inputOutput
  enabled SFBool inputOutput = TRUE
  hitNormal_changed SFVec3f outputOnly
  hitPoint_changed SFVec3f outputOnly
  hitTexCoord_changed SFVec2f outputOnly
  isActive SFBool outputOnly
  isOver SFBool outputOnly
  metadata SFNode inputOutput <X3DMetadataObject>
  touchTime SFTime outputOnly
node TransformSensor : X3DEnvironmentalSensorNode @children  # EnvironmentalSensor 3
  center SFVec3f inputOutput
  description SFString inputOutput
  enabled SFBool inputOutput = TRUE
  enterTime SFTime outputOnly
  exitTime SFTime outputOnly
  isActive SFBool outputOnly
  metadata SFNode inputOutput <X3DMetadataObject>
  orientation_changed SFRotation outputOnly
  position_changed SFVec3f outputOnly
  size SFVec3f inputOutput
  targetObject SFNode inputOutput <X3DGroupingNode|X3DShapeNode>
node TransmitterPdu : X3DNetworkSensorNode X3DBoundedObject @children  # DIS 1
  address SFString inputOutput = "localhost"
  antennaLocation SFVec3f inputOutput
  antennaPatternLength SFInt32 inputOutput
  antennaPatternType SFInt32 inputOutput
  applicationID SFInt32 inputOutput
  bboxCenter SFVec3f initializeOnly
  bboxDisplay SFBool inputOutput
  bboxSize SFVec3f initializeOnly = -1 -1 -1
  cryptoKeyID SFInt32 inputOutput
  cryptoSystem SFInt32 inputOutput
  description SFString inputOutput
  enabled SFBool inputOutput = TRUE
  entityID SFInt32 inputOutput
  frequency SFInt32 inputOutput
  geoCoords SFVec3d inputOutput
  geoSystem MFString initializeOnly = "GD" "WE"
  inputSource SFInt32 inputOutput
  isActive SFBool outputOnly
  isNetworkReader SFBool outputOnly
  isNetworkWriter SFBool outputOnly
  isRtpHeaderHeard SFBool outputOnly
  isStandAlone SFBool outputOnly
  lengthOfModulationParameters SFInt32 inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  modulationTypeDetail SFInt32 inputOutput
  modulationTypeMajor SFInt32 inputOutput
  modulationTypeSpreadSpectrum SFInt32 inputOutput
  modulationTypeSystem SFInt32 inputOutput
  multicastRelayHost SFString inputOutput
  multicastRelayPort SFInt32 inputOutput
  networkMode SFString inputOutput = "standAlone"
  port SFInt32 inputOutput
  power SFFloat inputOutput
  radioEntityTypeCategory SFInt32 inputOutput
  radioEntityTypeCountry SFInt32 inputOutput
  radioEntityTypeDomain SFInt32 inputOutput
  radioEntityTypeKind SFInt32 inputOutput
  radioEntityTypeNomenclature SFInt32 inputOutput
  radioEntityTypeNomenclatureVersion SFInt32 inputOutput
  radioID SFInt32 inputOutput
  readInterval SFTime inputOutput = 0.1
  relativeAntennaLocation SFVec3f inputOutput
  rtpHeaderExpected SFBool inputOutput
  siteID SFInt32 inputOutput
  timestamp SFTime outputOnly
  transmitFrequencyBandwidth SFFloat inputOutput
  transmitState SFInt32 inputOutput
  visible SFBool inputOutput = TRUE
  whichGeometry SFInt32 inputOutput = 1
  writeInterval SFTime inputOutput = 1
node TriangleFanSet : X3DComposedGeometryNode @geometry  # Rendering 3
  attrib MFNode inputOutput <X3DVertexAttributeNode>
  ccw SFBool initializeOnly = TRUE
  color SFNode inputOutput <X3DColorNode>
  colorPerVertex SFBool initializeOnly = TRUE
  coord SFNode inputOutput <X3DCoordinateNode>
  fanCount MFInt32 inputOutput
  fogCoord SFNode inputOutput <FogCoordinate>
  metadata SFNode inputOutput <X3DMetadataObject>
  normal SFNode inputOutput <X3DNormalNode>
  normalPerVertex SFBool initializeOnly = TRUE
  solid SFBool initializeOnly = TRUE
  texCoord SFNode inputOutput <X3DSingleTextureCoordinateNode|MultiTextureCoordinate>
node TriangleSet2D : X3DGeometryNode @geometry  # Geometry2D 1
  metadata SFNode inputOutput <X3DMetadataObject>
  solid SFBool initializeOnly
  vertices MFVec2f inputOutput
node TriangleStripSet : X3DComposedGeometryNode @geometry  # Rendering 3
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
  stripCount MFInt32 inputOutput
  texCoord SFNode inputOutput <X3DSingleTextureCoordinateNode|MultiTextureCoordinate>
node TwoSidedMaterial : X3DMaterialNode @material  # Shape 4
  ambientIntensity SFFloat inputOutput = 0.2
  backAmbientIntensity SFFloat inputOutput = 0.2
  backDiffuseColor SFColor inputOutput = 0.8 0.8 0.8
  backEmissiveColor SFColor inputOutput
  backShininess SFFloat inputOutput = 0.2
  backSpecularColor SFColor inputOutput
  backTransparency SFFloat inputOutput
  diffuseColor SFColor inputOutput = 0.8 0.8 0.8
  emissiveColor SFColor inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  separateBackColor SFBool inputOutput
  shininess SFFloat inputOutput = 0.2
  specularColor SFColor inputOutput
  transparency SFFloat inputOutput
node UnlitMaterial : X3DOneSidedMaterialNode @material  # Shape 1
  emissiveColor SFColor inputOutput = 1 1 1
  emissiveTexture SFNode inputOutput <X3DSingleTextureNode>
  emissiveTextureMapping SFString inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  normalScale SFFloat inputOutput = 1
  normalTexture SFNode inputOutput <X3DSingleTextureNode>
  normalTextureMapping SFString inputOutput
  transparency SFFloat inputOutput
node ViewpointGroup : X3DChildNode @children  # Navigation 3
  center SFVec3f inputOutput
  children MFNode inputOutput <X3DViewpointNode|ViewpointGroup>
  description SFString inputOutput
  displayed SFBool inputOutput = TRUE
  metadata SFNode inputOutput <X3DMetadataObject>
  retainUserOffsets SFBool inputOutput
  size SFVec3f inputOutput
node Viewport : X3DViewportNode @viewport  # Layering 1
  addChildren MFNode inputOnly <X3DChildNode>
  bboxCenter SFVec3f initializeOnly
  bboxDisplay SFBool inputOutput
  bboxSize SFVec3f initializeOnly = -1 -1 -1
  children MFNode inputOutput <X3DChildNode>
  clipBoundary MFFloat inputOutput = 0 1 0 1
  metadata SFNode inputOutput <X3DMetadataObject>
  removeChildren MFNode inputOnly <X3DChildNode>
  visible SFBool inputOutput = TRUE
node VisibilitySensor : X3DEnvironmentalSensorNode @children  # EnvironmentalSensor 2
  center SFVec3f inputOutput
  description SFString inputOutput
  enabled SFBool inputOutput = TRUE
  enterTime SFTime outputOnly
  exitTime SFTime outputOnly
  isActive SFBool outputOnly
  metadata SFNode inputOutput <X3DMetadataObject>
  size SFVec3f inputOutput
node VolumeData : X3DVolumeDataNode @children  # VolumeRendering 1
  bboxCenter SFVec3f initializeOnly
  bboxDisplay SFBool inputOutput
  bboxSize SFVec3f initializeOnly = -1 -1 -1
  dimensions SFVec3f inputOutput = 1 1 1
  metadata SFNode inputOutput <X3DMetadataObject>
  renderStyle SFNode inputOutput <X3DVolumeRenderStyleNode>
  visible SFBool inputOutput = TRUE
  voxels SFNode inputOutput <X3DTexture3DNode>
node VolumeEmitter : X3DParticleEmitterNode @emitter  # ParticleSystems 2
  coord SFNode inputOutput <X3DCoordinateNode>
  coordIndex MFInt32 initializeOnly = -1
  direction SFVec3f inputOutput = 0 1 0
  internal SFBool initializeOnly = TRUE
  mass SFFloat inputOutput
  metadata SFNode inputOutput <X3DMetadataObject>
  on SFBool inputOutput = TRUE
  set_coordIndex MFInt32 inputOnly
  speed SFFloat inputOutput
  surfaceArea SFFloat inputOutput
  variation SFFloat inputOutput = 0.25
node VolumePickSensor : X3DPickSensorNode @children  # Picking 3
  description SFString inputOutput
  enabled SFBool inputOutput = TRUE
  intersectionType SFString initializeOnly = "BOUNDS"
  isActive SFBool outputOnly
  matchCriterion SFString inputOutput = "MATCH_ANY"
  metadata SFNode inputOutput <X3DMetadataObject>
  objectType MFString inputOutput = "ALL"
  pickedGeometry MFNode outputOnly <X3DChildNode>
  pickingGeometry SFNode inputOutput <X3DGeometryNode>
  pickTarget MFNode inputOutput <X3DGroupingNode|X3DShapeNode|Inline>
  sortOrder SFString initializeOnly = "CLOSEST"
node WaveShaper : X3DSoundProcessingNode @children  # Sound 2
  channelCount SFInt32 outputOnly
  channelCountMode SFString inputOutput = "MAX"
  channelInterpretation SFString inputOutput = "SPEAKERS"
  children MFNode inputOutput <Analyser|AudioClip|AudioDestination|BiquadFilter|BufferAudioSource|ChannelMerger|ChannelSelector|ChannelSplitter|Convolver|Delay|DynamicsCompressor|Gain|ListenerPointSource|MicrophoneSource|MovieTexture|OscillatorSource|Sound|SpatialSound|StreamAudioDestination|StreamAudioSource|WaveShaper>
  description SFString inputOutput
  elapsedTime SFTime outputOnly
  enabled SFBool inputOutput = TRUE
  gain SFFloat inputOutput = 1
  isActive SFBool outputOnly
  isPaused SFBool outputOnly
  metadata SFNode inputOutput <X3DMetadataObject>
  oversample SFString inputOutput = "NONE"
  pauseTime SFTime inputOutput
  resumeTime SFTime inputOutput
  startTime SFTime inputOutput
  stopTime SFTime inputOutput
  tailTime SFTime inputOutput
node WindPhysicsModel : X3DParticlePhysicsModelNode @physics  # ParticleSystems 1
  direction SFVec3f inputOutput = 1 0 0
  enabled SFBool inputOutput = TRUE
  gustiness SFFloat inputOutput = 0.1
  metadata SFNode inputOutput <X3DMetadataObject>
  speed SFFloat inputOutput = 0.1
  turbulence SFFloat inputOutput
"""
