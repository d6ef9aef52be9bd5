// The counting `count_fragment_invocation()` (see fragment_counter.wgsl): one atomic add per
// fragment-shader invocation, read back by FragmentInvocationCounter.
@group(0) @binding(4) var<storage, read_write> fragment_invocations: atomic<u32>;

fn count_fragment_invocation() {
    atomicAdd(&fragment_invocations, 1u);
}
