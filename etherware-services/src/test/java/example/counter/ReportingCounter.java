package example.counter;

import io.etherware.core.component.Component;
import io.etherware.core.component.ComponentContext;
import io.etherware.core.component.ComponentState;
import io.etherware.core.message.ContentsTypes;
import io.etherware.core.message.Message;
import io.etherware.core.message.Profile;
import java.util.concurrent.atomic.AtomicInteger;

/**
 * Test component for migrations: counts {@link Seq} messages and reports each to {@link #SINK} as
 * a {@link Counted}, at the message's QoS; its count and last sequence are its state. The node that
 * handled a message is the node in the report's message id. The nodes it runs on or reports to
 * register its contents ({@link #register}) so they cross nodes.
 */
public class ReportingCounter implements Component {

    /** Where the reports go. */
    public static final Profile SINK = Profile.of("sink");

    protected long count;
    protected long lastSequence = -1;

    /** What the management service calls on a node's registry when it loads this class. */
    public static void registerContents(ContentsTypes types) {
        register(types);
    }

    /** Registers {@link Seq}, {@link Counted} and {@link CounterState} in {@code types}. */
    public static void register(ContentsTypes types) {
        types.register("test.seq", Seq.class);
        types.register("test.counted", Counted.class);
        types.register("test.counterState", CounterState.class);
    }

    @Override
    public void onMessage(Message message, ComponentContext context) {
        if (message.contents() instanceof Seq seq) {
            count++;
            lastSequence = seq.value();
            context.send(SINK, new Counted(seq.value(), count), message.qos());
        }
    }

    @Override
    public ComponentState snapshot() {
        return new CounterState(count, lastSequence);
    }

    @Override
    public void restore(ComponentState state) throws Exception {
        var counter = (CounterState) state;
        count = counter.count();
        lastSequence = counter.lastSequence();
    }

    /** Reports the Ticks it gets instead, their sequence as the report's sequence. */
    public static class TickReporter extends ReportingCounter {
        @Override
        public void onMessage(Message message, ComponentContext context) {
            if (message.contents() instanceof io.etherware.core.message.Tick tick) {
                count++;
                lastSequence = tick.sequence();
                context.send(SINK, new Counted(tick.sequence(), count), message.qos());
            }
        }
    }

    /**
     * Its construction takes {@link #CONSTRUCT_MS}: the target of a migration that does not finish
     * its PREPARE step in time.
     */
    public static class SlowConstruct extends ReportingCounter {
        public static final long CONSTRUCT_MS = 1_500;

        public SlowConstruct() {
            try {
                Thread.sleep(CONSTRUCT_MS);
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
            }
        }
    }

    /**
     * Its snapshot takes {@link #SNAPSHOT_MS}: the source of a migration that is killed while it
     * takes the state to ship.
     */
    public static class SlowSnapshot extends ReportingCounter {
        public static final long SNAPSHOT_MS = 1_500;

        @Override
        public ComponentState snapshot() {
            try {
                Thread.sleep(SNAPSHOT_MS);
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
            }
            return super.snapshot();
        }
    }

    /** Its restore always throws: a migration to it must roll back. */
    public static class FailingRestore extends ReportingCounter {
        @Override
        public void restore(ComponentState state) {
            throw new IllegalStateException("this test counter refuses every state");
        }
    }

    /**
     * Its restore takes {@link #RESTORE_MS}, longer than the migration step timeout of the tests
     * (2 s): the source's INSTALL step fails, and it resumes the component, before this is installed.
     */
    public static class TooSlowRestore extends ReportingCounter {
        public static final long RESTORE_MS = 3_000;

        @Override
        public void restore(ComponentState state) throws Exception {
            Thread.sleep(RESTORE_MS);
            super.restore(state);
        }
    }

    /** Its restore takes {@link #RESTORE_MS}: the target of a migration that does not answer in time. */
    public static class SlowRestore extends ReportingCounter {
        public static final long RESTORE_MS = 1_500;
        /** How many restores began in this JVM. */
        public static final AtomicInteger restoring = new AtomicInteger();

        @Override
        public void restore(ComponentState state) throws Exception {
            restoring.incrementAndGet();
            Thread.sleep(RESTORE_MS);
            super.restore(state);
        }
    }
}
