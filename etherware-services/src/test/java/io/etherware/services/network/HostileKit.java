package io.etherware.services.network;

import io.etherware.core.codec.MessageCodec;
import io.etherware.core.component.Component;
import io.etherware.core.kernel.RequestFailed;
import io.etherware.core.kernel.Undeliverable;
import io.etherware.core.message.Contents;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Message;
import io.etherware.core.message.MessageId;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import java.nio.charset.StandardCharsets;
import java.util.List;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.function.Supplier;

/**
 * The parts the hostile-peer tests share: the target's echo component, messages written by an
 * attacker, a heap gauge and an OutOfMemoryError watch.
 */
final class HostileKit {

    static final Profile ECHO = Profile.of("echo");
    static final QoS HIGH = QoS.of(Criticality.HIGH);
    static final long LEGIT_TIMEOUT_MS = 3_000;
    private static final MessageCodec CODEC = codec();

    private HostileKit() {
    }

    private static MessageCodec codec() {
        var types = Num.register(new io.etherware.core.message.ContentsTypes());
        io.etherware.core.kernel.EtherwareNode.registerContents(types);
        return new MessageCodec(types);
    }

    /** Answers every request with its own contents; ignores notices about its replies. */
    static Supplier<Component> echo() {
        return () -> (message, context) -> {
            if (message.hasSender() && !(message.contents() instanceof Undeliverable)
                    && !(message.contents() instanceof RequestFailed)) {
                context.reply(message, message.contents());
            }
        };
    }

    static Profile nodeProfile(String nodeId) {
        return Profile.of("etherware.node", "id", nodeId);
    }

    /** The XML of a message an attacker writes, with whatever id and correlation it likes. */
    static byte[] xml(Profile to, Profile sender, Contents contents, MessageId id, MessageId correlationId) {
        return CODEC.encode(new Message(to, sender, System.currentTimeMillis() * 1_000_000L, HIGH, contents, id,
                correlationId));
    }

    static Message decode(String xml) {
        return CODEC.decode(xml.getBytes(StandardCharsets.UTF_8));
    }

    /** Heap in use after full collections: what is retained, not garbage. */
    static long usedHeapAfterGc() {
        Runtime runtime = Runtime.getRuntime();
        long used = Long.MAX_VALUE;
        for (int i = 0; i < 3; i++) {
            System.gc();
            try {
                Thread.sleep(50);
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
            }
            used = Math.min(used, runtime.totalMemory() - runtime.freeMemory());
        }
        return used;
    }

    /** Records errors that escape any thread while it is open (an OutOfMemoryError among them). */
    static final class UncaughtWatch implements AutoCloseable {
        final List<Throwable> escaped = new CopyOnWriteArrayList<>();
        private final Thread.UncaughtExceptionHandler before = Thread.getDefaultUncaughtExceptionHandler();

        UncaughtWatch() {
            Thread.setDefaultUncaughtExceptionHandler((thread, error) -> {
                escaped.add(error);
                if (before != null) {
                    before.uncaughtException(thread, error);
                }
            });
        }

        boolean sawOutOfMemory() {
            return escaped.stream().anyMatch(OutOfMemoryError.class::isInstance);
        }

        @Override
        public void close() {
            Thread.setDefaultUncaughtExceptionHandler(before);
        }
    }
}
