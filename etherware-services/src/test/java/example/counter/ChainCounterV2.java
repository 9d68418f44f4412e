package example.counter;

/** Harness component: a second class with {@link ChainCounter}'s behaviour, to swap back and forth. */
public class ChainCounterV2 extends ChainCounter {
}
