#include "ParcelRouting.H"
#include "ParticleLocator.H"
#include "Pstream.H"
#include "IPstream.H"
#include "OPstream.H"

namespace
{

template<class T>
std::vector<T> toVector(const Foam::List<T>& list)
{
    return std::vector<T>(list.cbegin(), list.cend());
}

} // namespace


Foam::cosim::ParcelRouting::ParcelRouting(const treeBoundBox& myBounds)
{
    if (Pstream::parRun())
    {
        master_ = Pstream::master();
        bounds_.setSize(Pstream::nProcs());
        bounds_[Pstream::myProcNo()] = myBounds;
        Pstream::gatherList(bounds_);
        Pstream::scatterList(bounds_);
    }
}


bool Foam::cosim::ParcelRouting::reaches(label proc, const point& c, scalar r) const
{
    return ParticleLocator::inBox(bounds_[proc], c, r + 1e-12);
}


void Foam::cosim::ParcelRouting::send
(
    const std::vector<std::int64_t>& ids,
    const std::vector<double>& position,
    const std::vector<double>& radius,
    const std::vector<double>& velocity
)
{
    const label n = label(ids.size());
    List<DynamicList<label>> to(nProcs());
    holder_.setSize(n);
    reachesMe_.setSize(n);
    for (label i = 0; i < n; ++i)
    {
        const point c(position[3*i], position[3*i + 1], position[3*i + 2]);
        label holders = 0;
        label holder = -1;
        reachesMe_[i] = false;
        for (label proc = 0; proc < nProcs(); ++proc)
        {
            if (reaches(proc, c, radius[i]))
            {
                ++holders;
                holder = proc;
                if (proc == Pstream::masterNo())
                {
                    reachesMe_[i] = true;  // its own box: it keeps the parcel
                }
                else
                {
                    to[proc].append(i);
                }
            }
        }
        holder_[i] = holders > 1 ? label(-2) : holder;
    }
    const std::vector<double> none;
    const std::vector<double>& v = velocity.size() == 3*ids.size() ? velocity : none;
    sent_.setSize(nProcs());
    for (label proc = 1; proc < nProcs(); ++proc)
    {
        sent_[proc].transfer(to[proc]);
        const labelList& which = sent_[proc];
        OPstream out(Pstream::commsTypes::scheduled, proc);
        out << which << pick(ids, which, 1) << pick(position, which, 3)
            << pick(radius, which, 1) << pick(v, which, 3) << pick(holder_, which, 1);
    }
}


void Foam::cosim::ParcelRouting::receive
(
    std::vector<std::int64_t>& ids,
    std::vector<double>& position,
    std::vector<double>& radius,
    std::vector<double>& velocity
)
{
    IPstream in(Pstream::commsTypes::scheduled, Pstream::masterNo());
    List<std::int64_t> id;
    List<double> x, r, v;
    in >> global_ >> id >> x >> r >> v >> holder_;
    reachesMe_.setSize(holder_.size());
    reachesMe_ = true;  // sent here because it reaches this processor's box
    ids = toVector(id);
    position = toVector(x);
    radius = toVector(r);
    velocity = toVector(v);
}


void Foam::cosim::ParcelRouting::send(const std::vector<double>& values, label width) const
{
    for (label proc = 1; proc < nProcs(); ++proc)
    {
        OPstream out(Pstream::commsTypes::scheduled, proc);
        if (proc < sent_.size())
        {
            out << pick(values, sent_[proc], width);  // none (empty) stays none
        }
        else
        {
            out << List<double>();  // nothing placed yet: no parcel is this processor's
        }
    }
}


void Foam::cosim::ParcelRouting::receive(std::vector<double>& values) const
{
    IPstream in(Pstream::commsTypes::scheduled, Pstream::masterNo());
    List<double> part;
    in >> part;
    values = toVector(part);
}
