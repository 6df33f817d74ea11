// The index of this invocation's item in linear work (one invocation per item of a list), whose
// work groups continue along y past the 65535 along x that GL guarantees: gl/dispatch.h's
// dispatchLinear, and worklist_args.comp for the indirect dispatches. Include after the shader's
// local_size layout, which declares gl_WorkGroupSize.
uint linearInvocationIndex() {
  return (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * gl_WorkGroupSize.x +
         gl_LocalInvocationID.x;
}
