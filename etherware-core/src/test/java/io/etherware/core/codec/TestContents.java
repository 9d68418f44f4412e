package io.etherware.core.codec;

import io.etherware.core.message.Contents;
import io.etherware.core.message.ContentsTypes;
import io.etherware.core.message.MessageId;
import io.etherware.core.message.Profile;

import java.util.Arrays;
import java.util.List;
import java.util.Map;
import java.util.Objects;

/** Contents records exercising every field shape the codec supports, and a registry holding them. */
final class TestContents {

    private TestContents() {
    }

    /** A registry with the built-in types and every record below, except {@link Unregistered}. */
    static ContentsTypes registry() {
        return new ContentsTypes()
                .register("angles", Angles.class)
                .register("everything", Everything.class)
                .register("samples", Samples.class)
                .register("counter-state", CounterState.class)
                .register("holder", Holder.class)
                .register("log-line", LogLine.class)
                .register("node", Node.class)
                .register("typed", Typed.class)
                .register("with-map", WithMap.class);
    }

    /** The pendulum's encoder reading: a message with a few numeric fields. */
    record Angles(long sequence, int encoder1, int encoder2, long dspTimeUs) implements Contents {
    }

    enum Mode { IDLE, RUNNING, FAULT }

    record Point(double xM, double yM) {
    }

    /** Stand-in for the kernel's ComponentState: a sub-interface of Contents. */
    interface ComponentState extends Contents {
    }

    record CounterState(long count, String label) implements ComponentState {
    }

    /** Every scalar, boxed and structured shape except arrays. */
    record Everything(boolean flag, byte b, short s, char c, int i, long l, float f, double d,
                      Boolean boxedFlag, Integer boxedInt, Long boxedLong, Double boxedDouble, Character boxedChar,
                      String text, Mode mode, Profile target, MessageId ref, Point point,
                      List<Point> points, List<String> names, List<Long> numbers, List<List<Integer>> matrix,
                      List<Mode> modes) implements Contents {
    }

    /** Primitive arrays; equality by content, as records compare arrays by identity. */
    record Samples(double[] values, long[] stampsNs, int[] counts, byte[] raw) implements Contents {
        @Override
        public boolean equals(Object other) {
            return other instanceof Samples that
                    && Arrays.equals(values, that.values) && Arrays.equals(stampsNs, that.stampsNs)
                    && Arrays.equals(counts, that.counts) && Arrays.equals(raw, that.raw);
        }

        @Override
        public int hashCode() {
            return Objects.hash(Arrays.hashCode(values), Arrays.hashCode(stampsNs), Arrays.hashCode(counts),
                    Arrays.hashCode(raw));
        }

        @Override
        public String toString() {
            return "Samples[" + Arrays.toString(values) + ", " + Arrays.toString(stampsNs) + ", "
                    + Arrays.toString(counts) + ", " + Arrays.toString(raw) + "]";
        }
    }

    /** Polymorphic fields: any contents, a sub-interface, and a list of contents. */
    record Holder(Contents any, ComponentState state, List<Contents> many) implements Contents {
    }

    /** Has a field named like the envelope's root element. */
    record LogLine(String message, String level) implements Contents {
    }

    /** Recursive, for nesting depth. */
    record Node(String name, List<Node> children) implements Contents {
        static Node chain(int length) {
            Node node = new Node("leaf", List.of());
            for (int i = 1; i < length; i++) {
                node = new Node("n" + i, List.of(node));
            }
            return node;
        }
    }

    /** A component named like the type attribute. */
    record Typed(String type, int value) implements Contents {
    }

    /** A field type the codec cannot carry. */
    record WithMap(Map<String, String> map) implements Contents {
    }

    /** Never registered. */
    record Unregistered(int value) implements Contents {
    }
}
