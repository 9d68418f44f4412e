package example.counter;

import io.etherware.core.component.Component;
import io.etherware.core.component.ComponentContext;
import io.etherware.core.component.ComponentState;
import io.etherware.core.message.Message;

/**
 * Test component, version 1: counts {@link Seq} messages into the journal named by its
 * configuration; its count and last sequence are its state.
 */
public class SequenceCounter implements Component {

    private final Journal journal;
    private long count;
    private long lastSequence = -1;

    public SequenceCounter(String journalName) {
        this.journal = Journal.named(journalName);
    }

    /** The name this logic writes into the journal. */
    protected String version() {
        return "v1";
    }

    @Override
    public void onMessage(Message message, ComponentContext context) {
        if (message.contents() instanceof Seq seq) {
            count++;
            lastSequence = seq.value();
            journal.add(version(), seq.value(), count);
        }
    }

    @Override
    public ComponentState snapshot() {
        return new CounterState(count, lastSequence);
    }

    @Override
    public void restore(ComponentState state) {
        var counter = (CounterState) state;
        count = counter.count();
        lastSequence = counter.lastSequence();
    }
}
