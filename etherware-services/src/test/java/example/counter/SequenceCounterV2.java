package example.counter;

/** Test component, version 2: the same counting, journaled as {@code v2}. */
public class SequenceCounterV2 extends SequenceCounter {

    public SequenceCounterV2(String journalName) {
        super(journalName);
    }

    @Override
    protected String version() {
        return "v2";
    }
}
