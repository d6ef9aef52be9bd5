// Called at the top of fragment entry points that tests count (FragmentInvocationCounter swaps
// in fragment_counter_counting.wgsl); does nothing in a normal build.
fn count_fragment_invocation() {}
