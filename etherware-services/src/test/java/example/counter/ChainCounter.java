package example.counter;

import io.etherware.core.component.Component;
import io.etherware.core.component.ComponentContext;
import io.etherware.core.component.ComponentState;
import io.etherware.core.message.Message;

/**
 * Harness component: keeps exactly one message in flight to itself while {@link Chain#running},
 * so a message is always waiting when an upgrade swaps it, and checks that the sequence numbers
 * follow each other across swaps. Its count and last sequence are its state.
 */
public class ChainCounter implements Component {

    private long count;
    private long lastSequence = -1;

    @Override
    public void onMessage(Message message, ComponentContext context) {
        if (!(message.contents() instanceof Seq seq)) {
            return;
        }
        if (lastSequence >= 0 && seq.value() != lastSequence + 1) {
            Chain.broken(lastSequence, seq.value());
        }
        lastSequence = seq.value();
        count++;
        Chain.lastSequence = lastSequence;
        if (Chain.running) {
            context.send(context.self(), new Seq(lastSequence + 1), message.qos());
        } else {
            Chain.ended = true;
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
