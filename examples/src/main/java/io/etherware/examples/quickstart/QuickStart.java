package io.etherware.examples.quickstart;

import io.etherware.core.component.Component;
import io.etherware.core.component.ComponentContext;
import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.message.Contents;
import io.etherware.core.message.ContentsTypes;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Message;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.core.message.Text;
import io.etherware.core.message.Tick;
import io.etherware.rt.scheduling.RealtimeScheduler;
import io.etherware.services.network.NetworkConfig;
import io.etherware.services.network.NetworkMessenger;
import io.etherware.services.notifier.Notifier;
import io.etherware.services.notifier.NotifierConfig;
import io.etherware.services.notifier.NotifierReply;
import io.etherware.services.notifier.TickSubscribe;
import java.time.Duration;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicLong;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * The README's complete program: a room heater under control across two nodes in one JVM. Node
 * {@code plant} hosts the room (it answers a read with a {@link Reading} and applies each
 * {@link Heat}); node {@code control} runs the real-time scheduler, a Notifier, and the controller,
 * which the Notifier activates every 100 ms with a HIGH Tick. Each README Java block of the quick
 * start is an excerpt of this file ({@code ReadmeExamplesTest}), and {@code QuickStartIT} runs it.
 *
 * <p>Run it: {@code java --enable-native-access=ALL-UNNAMED -cp examples/target/examples-0.1.0-SNAPSHOT.jar
 * io.etherware.examples.quickstart.QuickStart 5} (seconds; default 3).
 */
public final class QuickStart {

    /** A temperature reading, on the wire as {@code quickstart.reading}. */
    public record Reading(double celsius) implements Contents {}

    /** A heater command, 0 (off) to 1 (full power), on the wire as {@code quickstart.heat}. */
    public record Heat(double power) implements Contents {}

    /** What a run did: cycles the controller closed, and the room's temperature at the end. */
    public record Result(long cycles, double celsius) {}

    private static final Logger LOG = LoggerFactory.getLogger(QuickStart.class);
    static final Profile ROOM = Profile.of("room", "id", "1");
    static final Profile CONTROLLER = Profile.of("controller", "room", "1");
    static final long PERIOD_NS = 100_000_000L; // 100 ms
    static final QoS CONTROL = QoS.periodic(Criticality.HIGH, PERIOD_NS);

    private QuickStart() {
    }

    /**
     * Runs the program for the seconds given as its first argument (default 3).
     *
     * @param args optional: the run time in seconds
     * @throws Exception if the nodes cannot start or the Notifier refuses the subscription
     */
    public static void main(String[] args) throws Exception {
        Duration runFor = Duration.ofSeconds(args.length > 0 ? Long.parseLong(args[0]) : 3);
        Result result = run(runFor);
        System.out.printf("%d control cycles; the room is at %.2f °C%n", result.cycles(), result.celsius());
    }

    /**
     * Starts both nodes, controls the room for {@code runFor}, and closes everything in order.
     *
     * @param runFor how long to control the room
     * @return what the run did
     * @throws Exception if the nodes cannot start or the Notifier refuses the subscription
     */
    public static Result run(Duration runFor) throws Exception {
        var room = new Room(15.0);
        var cycles = new AtomicLong();
        var subscribed = new CompletableFuture<NotifierReply>();
        // README example begins
        // Every node that carries these messages registers them under the same wire names.
        var types = new ContentsTypes()
                .register("quickstart.reading", Reading.class)
                .register("quickstart.heat", Heat.class);
        try (var plant = EtherwareNode.builder().nodeId("plant").contentsTypes(types).build().start();
             var plantNet = NetworkMessenger.start(plant, NetworkConfig.builder().listen("127.0.0.1", 0).build());
             var control = EtherwareNode.builder().nodeId("control").contentsTypes(types)
                     .scheduler(RealtimeScheduler::withDefaults).build().start(); // Table II dispatchers
             var controlNet = NetworkMessenger.start(control,
                     NetworkConfig.builder().peer(plantNet.localAddress()).build());
             // Declared last, closed first: the Ticks stop before the network and the nodes go.
             var notifier = Notifier.install(control, NotifierConfig.defaults())) {
            plant.add(ROOM, () -> room);
            if (!controlNet.awaitResolvable(ROOM, Duration.ofSeconds(5))) { // announced by plant
                throw new IllegalStateException("the room was never announced to the control node");
            }
            control.add(CONTROLLER, () -> new Controller(notifier.profile(), subscribed, cycles));
            NotifierReply answer = subscribed.get(5, TimeUnit.SECONDS); // throws if refused or unanswered
            LOG.info("subscribed: first Tick at {} ns", answer.firstReleaseNs());
            Thread.sleep(runFor); // the controller runs on its dispatcher meanwhile
        }
        // README example ends
        return new Result(cycles.get(), room.celsius());
    }

    /** The controller: every Tick it reads the room; every reading it answers with a heater command. */
    // README example begins
    static final class Controller implements Component {
        private final Profile notifier;
        private final CompletableFuture<NotifierReply> subscribed;
        private final AtomicLong cycles;

        Controller(Profile notifier, CompletableFuture<NotifierReply> subscribed, AtomicLong cycles) {
            this.notifier = notifier;
            this.subscribed = subscribed;
            this.cycles = cycles;
        }

        @Override
        public void onStart(ComponentContext context) {
            // A request, not a send: the Notifier's answer (accepted, or refused with the reason) comes back.
            context.request(notifier, TickSubscribe.periodic(Criticality.HIGH, PERIOD_NS)).whenComplete((reply, failure) -> {
                if (failure != null) {
                    subscribed.completeExceptionally(failure);
                } else if (reply.contentsAs(NotifierReply.class).accepted()) {
                    subscribed.complete(reply.contentsAs(NotifierReply.class));
                } else {
                    subscribed.completeExceptionally(new IllegalStateException(
                            "the Notifier refused: " + reply.contentsAs(NotifierReply.class).reason()));
                }
            });
        }

        @Override
        public void onMessage(Message message, ComponentContext context) {
            switch (message.contents()) {
                case Tick tick -> context.send(ROOM, new Text("read"), CONTROL); // tick.releaseNs(): when it was due
                case Reading reading -> {
                    double power = Math.clamp(0.5 * (21.0 - reading.celsius()), 0.0, 1.0);
                    context.send(ROOM, new Heat(power), CONTROL);
                    cycles.incrementAndGet();
                }
                default -> context.logger().warn("unexpected {}", message.contents());
            }
        }
    }
    // README example ends

    /** The plant: a room that warms with the heater's power and cools toward 10 °C outside. */
    static final class Room implements Component {
        private volatile double celsius;

        Room(double celsius) {
            this.celsius = celsius;
        }

        double celsius() {
            return celsius;
        }

        @Override
        public void onMessage(Message message, ComponentContext context) {
            switch (message.contents()) {
                case Text read -> context.reply(message, new Reading(celsius));
                case Heat heat -> celsius += 0.1 * (4.0 * heat.power() - 0.2 * (celsius - 10.0)); // one 100 ms step
                default -> context.logger().warn("unexpected {}", message.contents());
            }
        }
    }
}
