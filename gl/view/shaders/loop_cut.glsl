// Whether the driver cut this invocation's loops short (design §6, "The loop
// limit of CPU rasterizers"). llvmpipe keeps one budget of 65,535 loop
// iterations for all the loops of an invocation (per SIMD vector) and, once
// it is spent, ends every loop at its next iteration without a word. A probe
// loop at the end of the shader, whose trip count the compiler cannot know
// (uLoopProbe = 2), then stops after one trip: the invocation counts itself
// in loopCut[0], which the host reads back. On drivers without the limit
// uLoopProbe is 0 and the probe costs nothing. (Spending the budget on the
// very last iteration is reported too; that is rare and errs on the safe side.)

layout(std430, binding = SVO_BIND_VIEW_LOOP_CUT) restrict buffer LoopCut { uint loopCut[]; };

uniform int uLoopProbe;

void countIfLoopsWereCut()
{
    int trips = 0;
    for (int i = 0; i < uLoopProbe; ++i) ++trips;
    if (trips < uLoopProbe) atomicAdd(loopCut[0], 1u);
}
